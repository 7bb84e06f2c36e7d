#include "workstation_window.hpp"

#include "branch_list.hpp"
#include "dicom_browser.hpp"
#include "frame_log.hpp"
#include "job_panel.hpp"
#include "parameter_panel.hpp"
#include "priority_line_view.hpp"
#include "recovery.hpp"
#include "relation_wheel_view.hpp"
#include "script.hpp"
#include "window_surface.hpp"
#include "slice_view.hpp"
#include "tree_view.hpp"
#include "volume_view.hpp"
#include "workstation.hpp"

#include "io/png_output.hpp"
#include "pipeline/session.hpp"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <opencv2/core.hpp>

#include <GL/gl.h>

#include <chrono>
#include <future>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/resource.h>

namespace arbor::workstation {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> g_dropped; // filled by GLFW's drop callback on the UI thread

void on_drop(GLFWwindow *, int count, const char **paths)
{
    for (int i = 0; i < count; ++i)
        g_dropped.emplace_back(paths[i]);
}

void on_glfw_error(int code, const char *message) { std::fprintf(stderr, "arbor view: GLFW error %d: %s\n", code, message); }

// The window's pixels as drawn this frame (before the swap), top row first, BGR.
cv::Mat read_framebuffer(GLFWwindow *window)
{
    int w = 0, h = 0;
    glfwGetFramebufferSize(window, &w, &h);
    std::vector<uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_BACK);
    glReadPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, rgb.data());
    cv::Mat bgr(h, w, CV_8UC3);
    for (int y = 0; y < h; ++y) {
        const uint8_t *src = &rgb[static_cast<std::size_t>(h - 1 - y) * w * 3]; // GL rows start at the bottom
        uint8_t *dst = bgr.ptr<uint8_t>(y);
        for (int x = 0; x < w; ++x) {
            dst[3 * x] = src[3 * x + 2];
            dst[3 * x + 1] = src[3 * x + 1];
            dst[3 * x + 2] = src[3 * x];
        }
    }
    return bgr;
}

// The calling thread's CPU time and page faults so far.
struct ThreadUsage {
    double cpu_s = 0;
    long faults = 0;
};

ThreadUsage thread_usage()
{
    rusage u{};
    getrusage(RUSAGE_THREAD, &u);
    return {static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
                static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6,
            u.ru_minflt + u.ru_majflt};
}

class Window final : public ScriptWindow {
public:
    Window(Workstation &ws, const WindowOptions &options) : ws_(ws), options_(options) {}
    int run();

    void capture_window(const fs::path &path) override { capture_ = path; }
    void quit() override { quit_ = true; }
    bool busy() const override { return dicom_.scanning() || dicom_.pacs().searching(); }
    void pacs_search(const std::string &node, const std::vector<std::string> &filters) override
    {
        dicom::PacsQuery q;
        for (const std::string &f : filters) {
            const auto eq = f.find('=');
            const std::string key = f.substr(0, eq), value = eq == std::string::npos ? "" : f.substr(eq + 1);
            if (eq == std::string::npos)
                throw std::invalid_argument("'" + f + "': filters are KEY=VALUE");
            if (key == "patient")
                q.patient = value;
            else if (key == "study-date")
                q.study_date = value;
            else if (key == "modality")
                q.modality = value;
            else if (key == "accession")
                q.accession = value;
            else
                throw std::invalid_argument("unknown filter '" + key + "' (patient, study-date, modality, accession)");
        }
        dicom_.show_pacs();
        dicom_.pacs().search(node, q);
    }
    void pacs_open(std::size_t row) override
    {
        dicom_.pacs().poll();
        if (!dicom_.pacs().error().empty())
            throw std::runtime_error(dicom_.pacs().error());
        dicom_.pacs().open(row, ws_);
    }

private:
    void frame();
    void layout();
    void menu();
    void open(const fs::path &path);
    void dialogs();
    void help();
    void autosave();
    std::string job_summary() const;
    // Reports the window screenshots written (all of them, waiting, when `wait`).
    void finish_captures(bool wait);

    Workstation &ws_;
    const WindowOptions &options_;
    GLFWwindow *window_ = nullptr;
    std::shared_ptr<WindowSurface> surface_; // the 3D view's GPU frames (renderers that draw into OpenGL)
    std::optional<ScriptRunner> script_;
    std::optional<FrameLog> frame_log_;
    // Where the current frame's time goes, for the frame log's slow frames.
    std::string phases_;
    double phase_start_ = 0;
    void phase(const char *name)
    {
        if (!frame_log_)
            return;
        const double now = seconds();
        char text[48];
        std::snprintf(text, sizeof text, "%s%s %.1f", phases_.empty() ? "" : " ", name, (now - phase_start_) * 1000);
        phases_ += text;
        phase_start_ = now;
    }
    const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
    std::optional<fs::path> capture_;
    std::vector<std::future<fs::path>> captures_; // window screenshots being written
    bool quit_ = false;
    int status_ = 0;

    VolumeView volume_;
    SliceView slices_[3] = {SliceView(SliceOrientation::Axial), SliceView(SliceOrientation::Coronal),
                            SliceView(SliceOrientation::Sagittal)};
    TreeView tree_;
    PriorityLineView priority_;
    BranchList branches_;
    ParameterPanel parameters_;
    JobPanel jobs_;
    RelationWheelView wheel_;
    DicomBrowser dicom_;

    char path_entry_[1024] = "";
    bool open_dialog_ = false, save_dialog_ = false, restore_offer_ = false;
    std::string save_kind_; // "session", "screenshot", "window", "labels", "tf"
    Autosave autosave_;
};

std::string Window::job_summary() const
{
    std::string s;
    for (const auto &job : ws_.jobs()) {
        char part[64];
        std::snprintf(part, sizeof part, "%s%s:%.2f", s.empty() ? "" : ",", pipeline::stage_name(job->stage()), job->fraction());
        s += part;
    }
    return s;
}

void Window::finish_captures(bool wait)
{
    for (auto it = captures_.begin(); it != captures_.end();) {
        if (!wait && it->wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
            ++it;
            continue;
        }
        try {
            ws_.say(ARBOR_LOG_INFO, "wrote the window " + it->get().string());
        } catch (const std::exception &e) {
            ws_.say(ARBOR_LOG_ERROR, e.what());
            if (script_) {
                std::fprintf(stderr, "arbor view: screenshot-window: %s\n", e.what());
                status_ = 1;
                quit_ = true;
            }
        }
        it = captures_.erase(it);
    }
}

void Window::open(const fs::path &path)
{
    // A folder goes through the DICOM browser (one readable series opens at once).
    std::error_code ec;
    if (fs::is_directory(path, ec)) {
        dicom_.scan(path, true);
        add_recent_file(path);
        return;
    }
    try {
        ws_.open(path);
        add_recent_file(path);
    } catch (const std::exception &e) {
        ws_.say(ARBOR_LOG_ERROR, e.what());
    }
}

void Window::autosave()
{
    if (options_.recovery)
        autosave_.tick(ws_, seconds());
}

void Window::menu()
{
    if (!ImGui::BeginMainMenuBar())
        return;
    if (ImGui::BeginMenu("File")) {
        if (ImGui::MenuItem("Open...", "Ctrl+O"))
            open_dialog_ = true;
        if (ImGui::MenuItem("DICOM browser...", nullptr, dicom_.shown()))
            dicom_.shown() = !dicom_.shown();
        if (ImGui::BeginMenu("Open recent")) {
            for (const fs::path &p : recent_files())
                if (ImGui::MenuItem(p.string().c_str()))
                    open(p);
            ImGui::EndMenu();
        }
        ImGui::Separator();
        const auto save = [&](const char *label, const char *kind, const char *suggestion) {
            if (ImGui::MenuItem(label, nullptr, false, ws_.has_input())) {
                save_dialog_ = true;
                save_kind_ = kind;
                std::snprintf(path_entry_, sizeof path_entry_, "%s", suggestion);
            }
        };
        save("Save session...", "session", "session.json");
        save("Screenshot of the 3D view...", "screenshot", "view.png");
        save("Screenshot of the window...", "window", "window.png");
        save("Export label map...", "labels", "labels.nrrd");
        save("Export transfer functions...", "tf", "transfer-functions.json");
        ImGui::Separator();
        if (ImGui::MenuItem("Quit", "Ctrl+Q"))
            quit_ = true;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
        if (ImGui::MenuItem("Undo", "Ctrl+Z", false, ws_.history().can_undo()))
            ws_.undo();
        if (ImGui::MenuItem("Redo", "Ctrl+Y", false, ws_.history().can_redo()))
            ws_.redo();
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Slices")) {
        if (ImGui::MenuItem("Auto window", nullptr, ws_.view().window_preset == "auto"))
            ws_.window_preset("auto");
        for (const WindowPreset &p : ct_presets())
            if (ImGui::MenuItem(("CT " + p.name).c_str(), nullptr, ws_.view().window_preset == p.name))
                ws_.window_preset(p.name);
        ImGui::Separator();
        ImGui::MenuItem("Label overlay", nullptr, &ws_.view().overlay);
        ImGui::SetNextItemWidth(120);
        float opacity = static_cast<float>(ws_.view().overlay_opacity);
        if (ImGui::SliderFloat("overlay opacity", &opacity, 0, 1))
            ws_.view().overlay_opacity = opacity;
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("View")) {
        for (const char *v : {"anterior", "posterior", "left", "right", "superior", "inferior", "reset"})
            if (ImGui::MenuItem(v))
                ws_.standard_view(v);
        ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Help")) {
        ImGui::MenuItem("Mouse and keys", "F1", &ws_.view().help);
        ImGui::EndMenu();
    }
    const std::string name = ws_.has_input() ? ws_.input_name() : "no volume";
    ImGui::SameLine(ImGui::GetWindowWidth() - ImGui::CalcTextSize(name.c_str()).x - 20);
    ImGui::TextDisabled("%s", name.c_str());
    ImGui::EndMainMenuBar();
}

void Window::dialogs()
{
    if (open_dialog_) {
        ImGui::OpenPopup("Open");
        open_dialog_ = false;
    }
    if (save_dialog_) {
        ImGui::OpenPopup("Save");
        save_dialog_ = false;
    }
    if (ImGui::BeginPopupModal("Open", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted("A volume file (NRRD, NIfTI, MetaImage, VTK...), a DICOM folder or an arbor session:");
        ImGui::SetNextItemWidth(600);
        const bool enter = ImGui::InputText("##path", path_entry_, sizeof path_entry_, ImGuiInputTextFlags_EnterReturnsTrue);
        if (enter || ImGui::Button("Open")) {
            open(path_entry_);
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel"))
            ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
    if (ImGui::BeginPopupModal("Save", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::Text("Save the %s as:", save_kind_.c_str());
        ImGui::SetNextItemWidth(600);
        const bool enter = ImGui::InputText("##path", path_entry_, sizeof path_entry_, ImGuiInputTextFlags_EnterReturnsTrue);
        if (enter || ImGui::Button("Save")) {
            try {
                if (save_kind_ == "session")
                    ws_.save_session(path_entry_);
                else if (save_kind_ == "screenshot")
                    ws_.screenshot(path_entry_);
                else if (save_kind_ == "window")
                    capture_ = fs::path(path_entry_);
                else if (save_kind_ == "labels")
                    ws_.export_labels(path_entry_);
                else if (save_kind_ == "tf")
                    ws_.export_transfer_functions(path_entry_);
            } catch (const std::exception &e) {
                ws_.say(ARBOR_LOG_ERROR, e.what());
            }
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Cancel"))
            ImGui::CloseCurrentPopup();
        ImGui::EndPopup();
    }
    if (restore_offer_) {
        ImGui::OpenPopup("Restore");
        restore_offer_ = false;
    }
    if (ImGui::BeginPopupModal("Restore", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
        ImGui::TextUnformatted("Arbor did not quit normally last time. Restore that session?");
        if (ImGui::Button("Restore")) {
            open(recovery_path());
            ImGui::CloseCurrentPopup();
        }
        ImGui::SameLine();
        if (ImGui::Button("Discard")) {
            std::error_code ec;
            fs::remove(recovery_path(), ec);
            ImGui::CloseCurrentPopup();
        }
        ImGui::EndPopup();
    }
}

void Window::help()
{
    if (!ws_.view().help)
        return;
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    ImGui::SetNextWindowPos(ImVec2(display.x * 0.5f, display.y * 0.5f), ImGuiCond_Always, ImVec2(0.5f, 0.5f));
    ImGui::Begin("Mouse and keys", &ws_.view().help, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoCollapse);
    const char *lines[][2] = {
        {"3D view: left drag", "rotate"},
        {"3D view: middle drag, Shift+left drag", "pan"},
        {"3D view: right drag, wheel", "zoom"},
        {"3D view: left click", "pick the first opaque point, move the crosshair there"},
        {"3D view: A P L R S I", "anterior, posterior, left, right, superior, inferior view"},
        {"3D view: Home", "reset the view"},
        {"slice: wheel", "next / previous slice"},
        {"slice: left click", "move the crosshair, select the branch under it"},
        {"slice: right drag", "window (horizontal) and level (vertical)"},
        {"tree: hover, click", "a branch's measures; select it"},
        {"priority lines: drag", "the threshold (in another row: switch simplifier)"},
        {"Ctrl+Z, Ctrl+Y", "undo, redo"},
        {"Ctrl+O", "open a volume, DICOM folder or session (or drop it on the window)"},
        {"F1", "this help"},
    };
    if (ImGui::BeginTable("keys", 2)) {
        for (const auto &l : lines) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(l[0]);
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(l[1]);
        }
        ImGui::EndTable();
    }
    ImGui::End();
}

void Window::layout()
{
    const ImVec2 display = ImGui::GetIO().DisplaySize;
    const float top = ImGui::GetFrameHeight();
    const float left_w = 340, right_w = 380;
    const float centre_w = std::max(200.0f, display.x - left_w - right_w);
    const float h = display.y - top;
    const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoBringToFrontOnFocus;
    const auto place = [&](float x, float y, float w, float wh) {
        ImGui::SetNextWindowPos({x, y}, ImGuiCond_Always);
        ImGui::SetNextWindowSize({w, wh}, ImGuiCond_Always);
    };
    // Left: controls, legend, jobs.
    place(0, top, left_w, h * 0.55f);
    if (ImGui::Begin("Controls", nullptr, fixed))
        parameters_.draw(ws_);
    ImGui::End();
    place(0, top + h * 0.55f, left_w, h * 0.27f);
    if (ImGui::Begin("Relation wheel", nullptr, fixed))
        wheel_.draw(ws_);
    ImGui::End();
    place(0, top + h * 0.82f, left_w, h * 0.18f);
    if (ImGui::Begin("Jobs", nullptr, fixed))
        jobs_.draw(ws_);
    ImGui::End();
    phase("panels");
    // Centre: the 3D view over the three slice views.
    const float view_h = h * 0.64f;
    place(left_w, top, centre_w, view_h);
    ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, {0, 0});
    // The views that fill their windows draw no window background: one
    // fill of the screen less a frame on a software OpenGL (the clear colour
    // below is the style's window colour).
    if (ImGui::Begin("3D view", nullptr,
                     fixed | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse | ImGuiWindowFlags_NoBackground))
        volume_.draw(ws_);
    ImGui::End();
    ImGui::PopStyleVar();
    phase("3d");
    for (int i = 0; i < 3; ++i) {
        place(left_w + centre_w * i / 3.0f, top + view_h, centre_w / 3.0f, h - view_h);
        if (ImGui::Begin(orientation_name(slices_[i].orientation()), nullptr,
                         fixed | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse |
                             ImGuiWindowFlags_NoBackground))
            slices_[i].draw(ws_);
        ImGui::End();
    }
    phase("slices");
    // Right: tree, priority lines, branches.
    const float rx = left_w + centre_w;
    place(rx, top, right_w, h * 0.30f);
    if (ImGui::Begin("Tree", nullptr, fixed | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoBackground))
        tree_.draw(ws_);
    ImGui::End();
    phase("tree");
    place(rx, top + h * 0.30f, right_w, h * 0.32f);
    if (ImGui::Begin("Priority lines", nullptr, fixed | ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoBackground))
        priority_.draw(ws_);
    ImGui::End();
    phase("priority");
    place(rx, top + h * 0.62f, right_w, h * 0.38f);
    if (ImGui::Begin("Branches", nullptr, fixed))
        branches_.draw(ws_);
    ImGui::End();
    phase("branches");
}

void Window::frame()
{
    ImGuiIO &io = ImGui::GetIO();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    // Scripted steps come after the platform back end read the real input
    // and before ImGui sees it, as a person's would.
    phase("new-frame");
    if (script_ && !script_->done()) {
        try {
            script_->step(ws_, *this);
        } catch (const ScriptError &e) {
            std::fprintf(stderr, "arbor view: %s\n", e.what());
            status_ = 1;
            quit_ = true;
        }
    }
    for (const std::string &p : g_dropped)
        open(p);
    g_dropped.clear();
    phase("script");
    ImGui::NewFrame();
    ws_.poll();
    phase("poll");
    if (!io.WantTextInput) {
        if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Z, false))
            ws_.undo();
        if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Y, false))
            ws_.redo();
        if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_O, false))
            open_dialog_ = true;
        if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Q, false))
            quit_ = true;
        if (ImGui::IsKeyPressed(GLFW_KEY_F1, false))
            ws_.view().help = !ws_.view().help;
    }
    menu();
    phase("menu");
    layout();
    dialogs();
    dicom_.draw(ws_);
    help();
    ImGui::Render();
    phase("imgui");
    int fw = 0, fh = 0;
    glfwGetFramebufferSize(window_, &fw, &fh);
    glViewport(0, 0, fw, fh);
    const ImVec4 back = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
    glClearColor(back.x, back.y, back.z, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (capture_) {
        // Read now, encode on another thread: a PNG of the whole window
        // takes longer than a frame may.
        captures_.push_back(std::async(std::launch::async, [path = *capture_, image = read_framebuffer(window_)] {
            io::write_png(path, image);
            return path;
        }));
        capture_.reset();
    }
    phase("gl");
    glfwSwapBuffers(window_);
    phase("swap");
    finish_captures(false);
    autosave();
    phase("autosave");
}

int Window::run()
{
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        std::fprintf(stderr, "arbor view: no window system (is DISPLAY set? run under xvfb-run for tests)\n");
        return 2;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    window_ = glfwCreateWindow(options_.width, options_.height, "Arbor", nullptr, nullptr);
    if (!window_) {
        std::fprintf(stderr, "arbor view: cannot create an OpenGL 3.3 core window\n");
        glfwTerminate();
        return 2;
    }
    glfwMakeContextCurrent(window_);
    glfwSwapInterval(1);
    glfwSetDropCallback(window_, on_drop);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // the layout is the program's, not a file's
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window_, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");

    int status = 0;
    try {
        if (!options_.frame_log.empty())
            frame_log_.emplace(options_.frame_log);
        if (!options_.script.empty()) {
            std::ifstream in(options_.script);
            if (!in)
                throw ScriptError(options_.script.string() + ": cannot read the script");
            std::stringstream text;
            text << in.rdbuf();
            script_.emplace(parse_script(text.str(), options_.script.string()), options_.script.string());
        }
        // The views' memory before the first job (see SliceView::reserve):
        // a 3D view as large as the window, slices up to 1024 a side.
        {
            int fw = 0, fh = 0;
            glfwGetFramebufferSize(window_, &fw, &fh);
            volume_.reserve(static_cast<uint32_t>(std::max(fw, 16)), static_cast<uint32_t>(std::max(fh, 16)));
            for (SliceView &s : slices_)
                s.reserve();
        }
        // Renderers that draw into OpenGL (the GL ray caster) draw the 3D
        // view in a context that shares textures with this window's: its
        // frames are shown without a read back.
        try {
            surface_ = std::make_shared<WindowSurface>(window_);
            ws_.draw_on(surface_, read_frame);
        } catch (const std::exception &e) {
            ws_.say(ARBOR_LOG_WARNING, std::string("the 3D view's frames come through the CPU: ") + e.what());
        }
        if (options_.open)
            open(*options_.open);
        else if (options_.recovery && !script_ && fs::exists(recovery_path()))
            restore_offer_ = true;
        // A new 3D frame wakes the loop at once; input does anyway.
        ws_.volume_view().on_frame([] { glfwPostEmptyEvent(); });
        while (!quit_ && !glfwWindowShouldClose(window_)) {
            // Between events: a script steps at frame rate; while jobs run,
            // ten frames a second keep the progress bars moving (a software
            // OpenGL's frame costs what the jobs need: 30 ms of a core at
            // 1600x1000 on llvmpipe); idle, two.
            const bool scripted = script_ && !script_->done();
            glfwWaitEventsTimeout(scripted ? 1.0 / 60 : !ws_.idle() ? 0.1 : 0.5);
            const double begin = seconds();
            const ThreadUsage before = thread_usage();
            phases_.clear();
            phase_start_ = begin;
            frame();
            const double end = seconds();
            // The frame's own time: input, drawing and the swap (not the wait).
            if (frame_log_) {
                const ThreadUsage after = thread_usage();
                char usage[64];
                std::snprintf(usage, sizeof usage, "cpu %.1f faults %ld | ", (after.cpu_s - before.cpu_s) * 1000,
                              after.faults - before.faults);
                frame_log_->write(end, (end - begin) * 1000, job_summary(), usage + phases_);
            }
        }
        ws_.volume_view().on_frame({});
        finish_captures(true);
        for (const std::string &failure : ws_.finish_writes()) {
            std::fprintf(stderr, "arbor view: %s\n", failure.c_str());
            status_ = 1;
        }
        status = status_;
    } catch (const std::exception &e) {
        ws_.volume_view().on_frame({});
        std::fprintf(stderr, "arbor view: %s\n", e.what());
        status = 1;
    }
    if (options_.recovery && status == 0)
        autosave_.finish(); // a normal end: nothing to recover
    if (surface_) {
        volume_.let_go(); // the frame it holds
        ws_.draw_on(nullptr); // the view's thread lets the surface go
        surface_.reset();     // its textures die here, the window's context current
    }
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window_);
    glfwTerminate();
    return status;
}

} // namespace

int run_window(Workstation &workstation, const WindowOptions &options)
{
    Window window(workstation, options);
    return window.run();
}

} // namespace arbor::workstation
