#include "egl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace arbor::glraycast {

namespace {

std::string egl_error()
{
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
    return std::string("EGL error ") + code;
}

// Displays this plugin initialised, with how many contexts of ours use
// each.  The last one out terminates its display: Mesa then joins its
// rasteriser threads, so a process that forks afterwards (plugin-check
// runs each check in a child) initialises a fresh one instead of waiting
// on threads the fork did not copy.
std::mutex users_mutex;
std::map<void *, int> users;

void hold(void *display)
{
    std::lock_guard lock(users_mutex);
    ++users[display];
}

void drop(void *display)
{
    std::lock_guard lock(users_mutex);
    if (--users[display] <= 0) {
        users.erase(display);
        eglTerminate(display);
    }
}

// Destroys a context of ours and lets go of its display.
void close(void *display, void *context)
{
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    drop(display);
}

} // namespace

bool is_software_renderer(const std::string &renderer)
{
    std::string r = renderer;
    std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (const char *name : {"llvmpipe", "softpipe", "swiftshader", "software rasterizer", "swrast", "lavapipe"})
        if (r.find(name) != std::string::npos)
            return true;
    return false;
}

EglContext::EglContext()
{
    std::string why;
    const auto platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    const auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    // Graphics devices first: a hardware one wins; else the first that works.
    std::vector<void *> candidates;
    if (platform_display && query_devices) {
        EGLint count = 0;
        if (query_devices(0, nullptr, &count) && count > 0) {
            std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
            query_devices(count, devices.data(), &count);
            for (EGLint i = 0; i < count; ++i)
                if (EGLDisplay d = platform_display(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(i)], nullptr))
                    candidates.push_back(d);
        }
    }
    if (platform_display)
        if (EGLDisplay d = platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr))
            candidates.push_back(d);
    struct Kept {
        void *display = nullptr, *context = nullptr;
        std::string description;
    } software; // the first software rasteriser that worked
    for (void *d : candidates) {
        if (!open(d, why))
            continue;
        if (!software_) {
            if (software.context)
                close(software.display, software.context);
            make_current();
            return;
        }
        if (!software.context) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            software = {display_, context_, description_};
        } else {
            close(display_, context_);
        }
        display_ = context_ = nullptr;
    }
    if (software.context) {
        display_ = software.display;
        context_ = software.context;
        description_ = software.description;
        software_ = true;
        make_current();
        return;
    }
    throw std::runtime_error("no OpenGL 3.3 core context through EGL" + (why.empty() ? std::string() : ": " + why));
}

bool EglContext::open(void *display, std::string &why)
{
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display, &major, &minor)) {
        why = "eglInitialize failed (" + egl_error() + ")";
        return false;
    }
    hold(display);
    if (!eglBindAPI(EGL_OPENGL_API)) {
        why = "this EGL has no desktop OpenGL (" + egl_error() + ")";
        drop(display);
        return false;
    }
    const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                 EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
    if (!context) {
        why = "no OpenGL 3.3 core context (" + egl_error() + ")";
        drop(display);
        return false;
    }
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
        why = "a context without a surface is refused (" + egl_error() + ")";
        eglDestroyContext(display, context);
        drop(display);
        return false;
    }
    display_ = display;
    context_ = context;
    const auto text = [](GLenum name) {
        const GLubyte *s = glGetString(name);
        return s ? std::string(reinterpret_cast<const char *>(s)) : std::string("unknown");
    };
    const std::string renderer = text(GL_RENDERER);
    description_ = renderer + ", OpenGL " + text(GL_VERSION);
    software_ = is_software_renderer(renderer);
    return true;
}

EglContext::~EglContext()
{
    if (context_)
        close(display_, context_);
}

void EglContext::make_current()
{
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
        throw std::runtime_error("the OpenGL context cannot be made current (" + egl_error() + ")");
}

void EglContext::release()
{
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

} // namespace arbor::glraycast
