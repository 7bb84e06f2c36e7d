// vtk_renderer.cpp - org.arbor.renderer.vtk-reference: the same scene through
// VTK 9.1's vtkFixedPointVolumeRayCastMapper, off screen, as an independent
// reference for Arbor's ray caster (and the anchor of its speed benchmark).
// VTK's CPU mappers take one global transfer function, so this renderer
// does too: label maps with more than one label are refused.  Debian's VTK
// renders through X even off screen, so it needs a display (xvfb-run).
// arbor.renderer/2: the coarse pass is VTK's own interactive mode (the
// mapper adjusts its image sample distance to reach the desired update
// rate, from the time its last frames took): the anchor of the interactive
// benchmark.  Regions are cut out of a full frame; no supersampling.
#include <arbor/sdk/renderer.hpp>

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace arbor::vtkref {

const arbor_plugin_descriptor kVtkRendererDescriptor = {
    sizeof(arbor_plugin_descriptor),
    ARBOR_PLUGIN_FLAG_SERIALIZE,
    "org.arbor.renderer.vtk-reference",
    ARBOR_KIND_RENDERER,
    "VTK reference ray caster",
    "1.0.0",
    "Arbor",
    "VTK 9.1's CPU ray caster (vtkFixedPointVolumeRayCastMapper) with one global transfer function: an "
    "independent reference for comparisons. Needs an X display (run under xvfb-run).",
    "",
};

namespace {

template <class T>
void copy_voxels(const arbor_volume &v, T *out)
{
    const char *base = static_cast<const char *>(v.voxels);
    for (int64_t k = 0; k < v.dims[2]; ++k)
        for (int64_t j = 0; j < v.dims[1]; ++j)
            for (int64_t i = 0; i < v.dims[0]; ++i)
                std::memcpy(out++, base + i * v.strides[0] + j * v.strides[1] + k * v.strides[2], sizeof(T));
}

class VtkRenderer final : public sdk::Renderer {
public:
    explicit VtkRenderer(const arbor_host *host)
        : Renderer(kVtkRendererDescriptor, host,
                   {sdk::ParamSpec::real("sample-distance", "Sample distance", 0.5, 0.01, 10.0)
                        .unit("voxels")
                        .hint("Distance between samples along a ray, in units of the smallest voxel spacing"),
                    sdk::ParamSpec::boolean("shading", "Shading", true),
                    sdk::ParamSpec::real("ambient", "Ambient", 0.3, 0.0, 1.0).group("Shading"),
                    sdk::ParamSpec::real("diffuse", "Diffuse", 0.7, 0.0, 1.0).group("Shading"),
                    sdk::ParamSpec::real("specular", "Specular", 0.25, 0.0, 1.0).group("Shading"),
                    sdk::ParamSpec::real("shininess", "Shininess", 24.0, 1.0, 256.0).group("Shading"),
                    sdk::ParamSpec::real("interactive-update-rate", "Interactive update rate", 20.0, 0.1, 1000.0)
                        .unit("frames/s")
                        .hint("The coarse pass: VTK's desired update rate, which its mapper meets by casting fewer "
                              "rays (automatic image sample distance)")},
                   Interface::v2)
    {
    }

    void render_region(const arbor_render_request_v2 &request, arbor_image &out, const sdk::Task &task) override
    {
        if (request.pass == ARBOR_RENDER_PASS_SUPERSAMPLE)
            sdk::fail(ARBOR_ERROR_UNSUPPORTED, "the VTK reference renderer has no supersample pass");
        const char *display = std::getenv("DISPLAY");
        if (!display || !*display)
            sdk::fail(ARBOR_ERROR_UNSUPPORTED, "the VTK reference renderer needs an X display (Debian's VTK 9.1 "
                                               "renders through X even off screen): run under xvfb-run");
        if (request.labels && request.labels->label_count > 1)
            sdk::fail(ARBOR_ERROR_UNSUPPORTED, "the VTK reference renderer takes one global transfer function: "
                                               "VTK 9.1's CPU mapper has no label maps");
        const arbor_volume &v = *request.volume;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                if (std::fabs(v.direction[3 * r + c] - (r == c ? 1.0 : 0.0)) > 1e-9)
                    sdk::fail(ARBOR_ERROR_UNSUPPORTED, "the VTK reference renderer takes axis-aligned (LPS) grids only");
        if (v.voxels != voxels_ || request.volume_revision != revision_) {
            load(v);
            revision_ = request.volume_revision;
        }
        task.throw_if_cancelled();
        classify(*request.transfer_functions, std::min({v.spacing[0], v.spacing[1], v.spacing[2]}));

        if (!window_) {
            window_ = vtkSmartPointer<vtkRenderWindow>::New();
            window_->SetOffScreenRendering(1);
            window_->SetMultiSamples(0);
            renderer_ = vtkSmartPointer<vtkRenderer>::New();
            window_->AddRenderer(renderer_);
            renderer_->AddVolume(volume_);
        }
        const bool interactive = request.pass == ARBOR_RENDER_PASS_COARSE;
        mapper_->SetAutoAdjustSampleDistances(interactive ? 1 : 0);
        if (!interactive)
            mapper_->SetImageSampleDistance(1.0);
        window_->SetDesiredUpdateRate(interactive ? params().number("interactive-update-rate") : 0.0001);
        const uint32_t width = request.frame_width, height = request.frame_height;
        window_->SetSize(static_cast<int>(width), static_cast<int>(height));
        renderer_->SetBackground(request.background[0], request.background[1], request.background[2]);
        const arbor_camera &c = *request.camera;
        vtkCamera *camera = renderer_->GetActiveCamera();
        camera->SetPosition(c.position);
        camera->SetFocalPoint(c.focal_point);
        camera->SetViewUp(c.view_up);
        camera->SetParallelProjection(c.projection == ARBOR_PROJECTION_ORTHOGRAPHIC);
        camera->SetViewAngle(c.view_angle);
        camera->SetParallelScale(c.parallel_scale);
        renderer_->ResetCameraClippingRange();
        window_->Render();

        vtkNew<vtkWindowToImageFilter> grab;
        grab->SetInput(window_);
        grab->SetInputBufferTypeToRGB();
        grab->ReadFrontBufferOff();
        grab->Update();
        vtkUnsignedCharArray *pixels = vtkUnsignedCharArray::SafeDownCast(grab->GetOutput()->GetPointData()->GetScalars());
        if (!pixels || pixels->GetNumberOfTuples() != static_cast<vtkIdType>(width) * height)
            sdk::fail(ARBOR_ERROR_INTERNAL, "VTK returned no image of the requested size");
        const int64_t depth_stride =
            ARBOR_HAS_FIELD(arbor_image, out.struct_size, depth_stride) && out.depth_stride > 0 ? out.depth_stride : static_cast<int64_t>(out.width);
        for (uint32_t y = 0; y < out.height; ++y) { // VTK's rows run bottom-up
            const uint32_t fy = request.region_y + y;
            for (uint32_t x = 0; x < out.width; ++x) {
                const uint32_t fx = request.region_x + x;
                const unsigned char *p = pixels->GetPointer(3 * ((static_cast<vtkIdType>(height) - 1 - fy) * width + fx));
                float *q = out.rgba + y * out.row_stride + 4 * x;
                for (int ch = 0; ch < 3; ++ch)
                    q[ch] = p[ch] / 255.0f;
                q[3] = 1.0f; // composited over the (opaque) background
            }
            if (out.depth) // VTK does not report it
                std::fill_n(out.depth + y * depth_stride, out.width, std::numeric_limits<float>::infinity());
        }
    }

private:
    void load(const arbor_volume &v)
    {
        image_ = vtkSmartPointer<vtkImageData>::New();
        image_->SetDimensions(static_cast<int>(v.dims[0]), static_cast<int>(v.dims[1]), static_cast<int>(v.dims[2]));
        image_->SetSpacing(v.spacing);
        image_->SetOrigin(v.origin);
        switch (v.voxel_type) { // the mapper's native types, others as float
        case ARBOR_VOXEL_U8:
            image_->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
            copy_voxels(v, static_cast<uint8_t *>(image_->GetScalarPointer()));
            break;
        case ARBOR_VOXEL_U16:
            image_->AllocateScalars(VTK_UNSIGNED_SHORT, 1);
            copy_voxels(v, static_cast<uint16_t *>(image_->GetScalarPointer()));
            break;
        case ARBOR_VOXEL_I16:
            image_->AllocateScalars(VTK_SHORT, 1);
            copy_voxels(v, static_cast<int16_t *>(image_->GetScalarPointer()));
            break;
        default: {
            image_->AllocateScalars(VTK_FLOAT, 1);
            float *out = static_cast<float *>(image_->GetScalarPointer());
            const char *base = static_cast<const char *>(v.voxels);
            const uint32_t size = arbor_voxel_size(v.voxel_type);
            for (int64_t k = 0; k < v.dims[2]; ++k)
                for (int64_t j = 0; j < v.dims[1]; ++j)
                    for (int64_t i = 0; i < v.dims[0]; ++i) {
                        const char *p = base + i * v.strides[0] + j * v.strides[1] + k * v.strides[2];
                        double x = 0;
                        switch (v.voxel_type) {
                        case ARBOR_VOXEL_I8: { int8_t t; std::memcpy(&t, p, size); x = t; break; }
                        case ARBOR_VOXEL_U32: { uint32_t t; std::memcpy(&t, p, size); x = t; break; }
                        case ARBOR_VOXEL_I32: { int32_t t; std::memcpy(&t, p, size); x = t; break; }
                        case ARBOR_VOXEL_F32: { float t; std::memcpy(&t, p, size); x = t; break; }
                        default: { double t; std::memcpy(&t, p, sizeof t); x = t; break; }
                        }
                        *out++ = static_cast<float>(x);
                    }
        }
        }
        if (!mapper_) {
            mapper_ = vtkSmartPointer<vtkFixedPointVolumeRayCastMapper>::New();
            mapper_->SetAutoAdjustSampleDistances(0);
            mapper_->SetLockSampleDistanceToInputSpacing(0);
            mapper_->SetImageSampleDistance(1.0);
            volume_ = vtkSmartPointer<vtkVolume>::New();
            volume_->SetMapper(mapper_);
            property_ = vtkSmartPointer<vtkVolumeProperty>::New();
            property_->SetInterpolationTypeToLinear();
            volume_->SetProperty(property_);
        }
        mapper_->SetInputData(image_);
        voxels_ = v.voxels;
    }

    // Transfer function 0 as VTK's colour and opacity functions.
    void classify(const arbor_tf_set &tf, double min_spacing)
    {
        vtkNew<vtkColorTransferFunction> colour;
        vtkNew<vtkPiecewiseFunction> opacity;
        const double lo = tf.domain[0], hi = tf.domain[1];
        for (uint32_t i = 0; i < tf.lut_size; ++i) {
            const float *e = tf.lut + 4 * i;
            const double value = hi > lo ? lo + (hi - lo) * i / (tf.lut_size - 1.0) : lo + i;
            colour->AddRGBPoint(value, e[0], e[1], e[2]);
            opacity->AddPoint(value, e[3]);
        }
        property_->SetColor(colour);
        property_->SetScalarOpacity(opacity);
        property_->SetScalarOpacityUnitDistance(tf.opacity_unit_distance);
        property_->SetShade(params().flag("shading") ? 1 : 0);
        property_->SetAmbient(params().number("ambient"));
        property_->SetDiffuse(params().number("diffuse"));
        property_->SetSpecular(params().number("specular"));
        property_->SetSpecularPower(params().number("shininess"));
        const double step = params().number("sample-distance") * min_spacing;
        mapper_->SetSampleDistance(step);
        mapper_->SetInteractiveSampleDistance(step);
    }

    vtkSmartPointer<vtkImageData> image_;
    vtkSmartPointer<vtkFixedPointVolumeRayCastMapper> mapper_;
    vtkSmartPointer<vtkVolume> volume_;
    vtkSmartPointer<vtkVolumeProperty> property_;
    vtkSmartPointer<vtkRenderWindow> window_;
    vtkSmartPointer<vtkRenderer> renderer_;
    const void *voxels_ = nullptr;
    uint64_t revision_ = ~uint64_t{0};
};

} // namespace

sdk::Instance *create_vtk_renderer(const arbor_host *host)
{
    return new VtkRenderer(host);
}

} // namespace arbor::vtkref

namespace {

const arbor::sdk::PluginClass kRenderers[] = {
    {&arbor::vtkref::kVtkRendererDescriptor, &arbor::vtkref::create_vtk_renderer},
};

} // namespace

ARBOR_SDK_DEFINE_LIBRARY(kRenderers)
