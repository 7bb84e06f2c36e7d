#include "phantom.hpp"

#include "core/voxel_type.hpp"

#include <embedded_resources.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace arbor::io {

namespace {

// splitmix64: tiny, fast and specified bit for bit.
class SplitMix64 {
public:
    explicit SplitMix64(uint64_t seed) : state_(seed) {}
    uint64_t next()
    {
        uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; } // [0, 1)
    double normal()
    {
        // Box-Muller; u1 in (0, 1] avoids log(0).
        const double u1 = 1.0 - uniform();
        const double u2 = uniform();
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
    }

private:
    uint64_t state_;
};

std::array<double, 3> vec3(const nlohmann::json &j, const std::string &what)
{
    if (!j.is_array() || j.size() != 3)
        throw std::invalid_argument(what + " must be an array of three numbers");
    std::array<double, 3> v{};
    for (int i = 0; i < 3; ++i) {
        if (!j[i].is_number())
            throw std::invalid_argument(what + " must be an array of three numbers");
        v[i] = j[i].get<double>();
    }
    return v;
}

// Normalised ellipsoidal radius of p relative to a structure (1 on the surface).
double ellipsoid_radius(const PhantomStructure &s, const std::array<double, 3> &p)
{
    double q2 = 0.0;
    for (int a = 0; a < 3; ++a) {
        const double d = (p[a] - s.center[a]) / s.radii[a];
        q2 += d * d;
    }
    return std::sqrt(q2);
}

double smoothstep(double x)
{
    x = std::clamp(x, 0.0, 1.0);
    return x * x * (3.0 - 2.0 * x);
}

const PhantomStructure *find(const PhantomRecipe &r, const std::string &name)
{
    for (const auto &s : r.structures)
        if (s.name == name)
            return &s;
    return nullptr;
}

} // namespace

PhantomRecipe parse_phantom_recipe(std::string_view text)
{
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error &e) {
        throw std::invalid_argument(std::string("phantom recipe is not valid JSON: ") + e.what());
    }
    try {
        PhantomRecipe r;
        r.name = j.at("name").get<std::string>();
        r.description = j.value("description", "");
        r.field_of_view_mm = j.value("field_of_view_mm", 200.0);
        r.voxel_type = voxel_type_from_name(j.value("voxel_type", "u16"));
        if (r.voxel_type == ARBOR_VOXEL_UNKNOWN)
            throw std::invalid_argument("phantom recipe: unknown voxel_type");
        r.value_unit = j.value("value_unit", "");
        r.background = j.value("background", 0.0);
        r.edge_voxels = j.value("edge_voxels", 1.0);
        for (const auto &js : j.at("structures")) {
            PhantomStructure s;
            s.name = js.at("name").get<std::string>();
            const std::string mode = js.value("mode", "paint");
            if (mode != "paint" && mode != "add")
                throw std::invalid_argument("structure " + s.name + ": mode must be paint or add");
            s.mode = mode == "add" ? PhantomStructure::Mode::Add : PhantomStructure::Mode::Paint;
            s.center = vec3(js.at("center"), "structure " + s.name + " center");
            s.radii = vec3(js.at("radii"), "structure " + s.name + " radii");
            for (double rr : s.radii)
                if (!(rr > 0))
                    throw std::invalid_argument("structure " + s.name + ": radii must be positive");
            s.edge = js.at("edge").get<double>();
            s.peak = js.at("peak").get<double>();
            r.structures.push_back(std::move(s));
        }
        if (j.contains("blobs")) {
            const auto &b = j["blobs"];
            r.blob_inside = b.value("inside", std::vector<std::string>{});
            r.blob_avoid = b.value("avoid", std::vector<std::string>{});
            r.blob_radius_voxels = b.value("radius_voxels", 1.0);
            r.blob_value = b.value("value", 0.0);
            for (const auto &n : r.blob_inside)
                if (!find(r, n))
                    throw std::invalid_argument("blobs: no structure named " + n);
            for (const auto &n : r.blob_avoid)
                if (!find(r, n))
                    throw std::invalid_argument("blobs: no structure named " + n);
        }
        return r;
    } catch (const nlohmann::json::exception &e) {
        throw std::invalid_argument(std::string("phantom recipe: ") + e.what());
    }
}

std::vector<std::string> builtin_phantom_kinds()
{
    return {"head"};
}

PhantomRecipe builtin_phantom(std::string_view kind)
{
    const auto text = embedded_resource("phantoms/" + std::string(kind) + ".json");
    if (!text)
        throw std::invalid_argument("unknown phantom kind '" + std::string(kind) +
                                    "' (built-in: head)");
    return parse_phantom_recipe(*text);
}

Volume make_phantom(const PhantomRecipe &recipe, const PhantomOptions &options)
{
    const int64_t n = options.size;
    if (n < 8 || n > 1024)
        throw std::invalid_argument("phantom size " + std::to_string(n) +
                                    " must lie in [8, 1024]");
    if (!(options.noise_sigma >= 0) || !std::isfinite(options.noise_sigma))
        throw std::invalid_argument("phantom noise must be a non-negative number");
    if (options.blobs < 0 || options.blobs > 10000)
        throw std::invalid_argument("phantom blob count must lie in [0, 10000]");

    Geometry g;
    g.dims = {n, n, n};
    const double spacing = recipe.field_of_view_mm / static_cast<double>(n);
    g.spacing = {spacing, spacing, spacing};
    // Centre the grid on the LPS origin.
    const double half = 0.5 * spacing * static_cast<double>(n - 1);
    g.origin = {-half, -half, -half};

    // Values in double first; quantised at the end.
    const std::size_t count = static_cast<std::size_t>(n * n * n);
    std::vector<double> f(count, recipe.background);
    const double voxel = 2.0 / static_cast<double>(n); // normalised units per voxel
    const auto coord = [&](int64_t i) { return (static_cast<double>(i) + 0.5) * voxel - 1.0; };

    const auto paint = [&](const PhantomStructure &s, double edge_voxels) {
        const double min_radius = std::min({s.radii[0], s.radii[1], s.radii[2]});
        const double width = std::max(edge_voxels * voxel, 1e-9);
        const double reach = 1.0 + width / min_radius;
        int64_t lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max<int64_t>(0, static_cast<int64_t>(std::floor(
                                             (s.center[a] - s.radii[a] * reach + 1.0) / voxel)));
            hi[a] = std::min<int64_t>(n - 1, static_cast<int64_t>(std::ceil(
                                                 (s.center[a] + s.radii[a] * reach + 1.0) / voxel)));
        }
        for (int64_t k = lo[2]; k <= hi[2]; ++k)
            for (int64_t j = lo[1]; j <= hi[1]; ++j)
                for (int64_t i = lo[0]; i <= hi[0]; ++i) {
                    const double q = ellipsoid_radius(s, {coord(i), coord(j), coord(k)});
                    const std::size_t v = static_cast<std::size_t>(i + n * (j + n * k));
                    const double inner = std::max(0.0, 1.0 - q * q);
                    if (s.mode == PhantomStructure::Mode::Add) {
                        // Smooth bump, C1 at the boundary: no ring artefacts.
                        f[v] += s.edge + (s.peak - s.edge) * inner * inner;
                    } else {
                        const double distance = (q - 1.0) * min_radius; // approximate
                        const double w = smoothstep(0.5 - distance / width);
                        const double value = s.edge + (s.peak - s.edge) * inner;
                        f[v] = f[v] * (1.0 - w) + value * w;
                    }
                }
    };

    for (const auto &s : recipe.structures)
        paint(s, recipe.edge_voxels);

    SplitMix64 rng(options.seed * 0x2545f4914f6cdd1dULL + 1);
    if (options.blobs > 0) {
        if (recipe.blob_inside.empty())
            throw std::invalid_argument("phantom '" + recipe.name + "' defines no blob region");
        const double r = recipe.blob_radius_voxels * voxel;
        int placed = 0;
        for (int attempt = 0; placed < options.blobs && attempt < options.blobs * 10000; ++attempt) {
            const std::array<double, 3> c{rng.uniform() * 2 - 1, rng.uniform() * 2 - 1,
                                          rng.uniform() * 2 - 1};
            bool inside = false;
            for (const auto &name : recipe.blob_inside) {
                const PhantomStructure &s = *find(recipe, name);
                // Keep the whole blob, with its smooth edge, inside.
                inside = inside || ellipsoid_radius(s, c) + 2 * r / std::min({s.radii[0], s.radii[1], s.radii[2]}) < 1.0;
            }
            bool avoided = true;
            for (const auto &name : recipe.blob_avoid) {
                const PhantomStructure &s = *find(recipe, name);
                avoided = avoided && ellipsoid_radius(s, c) > 1.0 + 2 * r / std::min({s.radii[0], s.radii[1], s.radii[2]});
            }
            if (!inside || !avoided)
                continue;
            PhantomStructure blob;
            blob.name = "blob";
            blob.center = c;
            blob.radii = {r, r, r};
            blob.edge = recipe.blob_value;
            blob.peak = recipe.blob_value;
            paint(blob, 0.5);
            ++placed;
        }
        if (placed < options.blobs)
            throw std::invalid_argument("could not place " + std::to_string(options.blobs) +
                                        " blobs in phantom '" + recipe.name + "'");
    }

    if (options.noise_sigma > 0)
        for (double &x : f)
            x += options.noise_sigma * rng.normal();

    ValueMapping mapping;
    mapping.unit = recipe.value_unit;
    Volume volume = Volume::allocate(recipe.voxel_type, g, mapping,
                                     std::numeric_limits<uint64_t>::max());
    dispatch_voxel_type(recipe.voxel_type, [&](auto t) {
        using T = decltype(t);
        T *out = volume.as<T>();
        for (std::size_t v = 0; v < count; ++v) {
            if constexpr (std::is_floating_point_v<T>) {
                out[v] = static_cast<T>(f[v]);
            } else {
                const double lo = static_cast<double>(std::numeric_limits<T>::min());
                const double hi = static_cast<double>(std::numeric_limits<T>::max());
                out[v] = static_cast<T>(std::clamp(std::round(f[v]), lo, hi));
            }
        }
    });
    return volume;
}

} // namespace arbor::io

namespace arbor::io {

std::vector<uint32_t> phantom_structure_labels(const PhantomRecipe &recipe, int64_t size)
{
    if (size < 8 || size > 1024)
        throw std::invalid_argument("phantom size " + std::to_string(size) + " must lie in [8, 1024]");
    const std::size_t n = static_cast<std::size_t>(size);
    std::vector<uint32_t> labels(n * n * n, 0);
    const double voxel = 2.0 / static_cast<double>(size);
    const auto coord = [&](std::size_t i) { return (static_cast<double>(i) + 0.5) * voxel - 1.0; };
    for (std::size_t k = 0; k < n; ++k)
        for (std::size_t j = 0; j < n; ++j)
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t s = 0; s < recipe.structures.size(); ++s)
                    if (ellipsoid_radius(recipe.structures[s], {coord(i), coord(j), coord(k)}) < 1.0)
                        labels[i + n * (j + n * k)] = static_cast<uint32_t>(s + 1);
    return labels;
}

} // namespace arbor::io
