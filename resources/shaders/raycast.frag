// raycast.frag - emission-absorption ray casting, the optical model of the
// CPU ray caster (plugins/renderer-cpu/ray_caster.cpp), sample for sample:
// front to back on the global lattice t = n * step + offset (offset a fixed
// per-pixel fraction of a step when jittered; where the ray enters or
// leaves through the volume's faces, the first and last samples' opacity
// corrected for the part of their step inside), trilinear values,
// post-classification with the lookup table of the sample's label
// (premultiplied, opacity corrected for the step), boundary emphasis from
// the gradient magnitude, Blinn-Phong with a headlight and two-sided
// normals, early ray termination, empty 8^3 blocks skipped.
//
// Variants are chosen when the program is built (llvmpipe runs both sides
// of a uniform branch): LABELLED, RESOLVE (a sample in a cell of mixed
// labels takes the label its value implies, walking the labels' tree as
// plugins/raycast/label_tree.hpp does; with REFINE, outside the coarse
// pass, a step in such a cell whose labels differ across it is taken as
// four samples; else the nearest
// voxel's label), SMOOTH (the gradient
// at the sample, trilinear between the voxels', as
// plugins/raycast/cell_sample.hpp, or with ISOTROPIC on thick slices
// as on the volume resampled to isotropic voxels; else the nearest
// voxel's), SHADED,
// BOUNDARY, JITTER, OCCLUSION (local ambient occlusion darkens the lit
// colour, plugins/raycast/local_occlusion.hpp), and VISIBILITY (instead of
// colour: what each of 32 labels from u_visibility_base contributes,
// T * alpha, into 8 RGBA targets).

uniform sampler3D u_values;   // R32F, linear: voxel centre (i, j, k) at ((i, j, k) + 0.5) / dims
uniform usampler3D u_labels;  // R16UI or R32UI: label << 1 | (the cell at this voxel has corners of other labels)
uniform isampler3D u_normals; // RGBA8I: xyz unit gradient * 127 (0: flat), w gradient magnitude - 128
uniform usampler3D u_blocks;  // R8UI per 8^3 block: 1 when every sample in it is transparent
uniform sampler2D u_lut;      // RGBA32F, a row per label
uniform sampler2D u_refined;  // the same for a quarter of the step (mixed cells' samples)
uniform sampler2D u_ranges;   // RGBA32F, one row: per label (low, scale, last)
uniform sampler2D u_factors;  // R32F: row 0 boundary factor per gradient byte, row 1 highlight per ndl * 256
uniform sampler2D u_occlusion; // RGBA32F, a row per label: the lookup tables of an occlusion ray's step
uniform vec3 u_occlusion_world[14]; // occlusion rays: unit directions in mm
uniform vec3 u_occlusion_step[14];  // and one step along each in voxel coordinates
uniform sampler2D u_tree;     // RGBA32F, one row: per label (parent, depth, saddle value)

uniform ivec3 u_dims;
uniform vec3 u_origin;        // LPS of voxel (0, 0, 0)
uniform mat3 u_to_voxel;      // LPS mm -> voxel index offsets
uniform vec3 u_content_low, u_content_high; // voxel-index box around the non-empty blocks

uniform vec3 u_eye, u_forward, u_right, u_up;
uniform bool u_perspective;
uniform float u_half, u_aspect;
uniform vec2 u_frame;         // frame size in pixels
uniform vec2 u_base;          // frame position of fragment (0, 0) (before u_subpixel)
uniform float u_spacing;      // frame pixels between neighbouring fragments
uniform vec2 u_subpixel;      // where in its pixel a fragment's ray goes
uniform float u_shift;        // supersampling: moves each ray's start, fract(0.618 * sample)
uniform float u_step;         // mm
uniform float u_termination;
uniform vec4 u_background;
uniform float u_ambient, u_diffuse;
uniform float u_occlusion_strength;
uniform int u_visibility_base;

#ifdef VISIBILITY
out vec4 o_visibility[8]; // locations 0-7
#else
out vec4 o_rgba;   // location 0
out float o_depth; // location 1; -1: opacity never reached 1/2
#endif

float pixel_hash(uvec2 p)
{
    uint h = p.x * 0x8da6b343u ^ p.y * 0xd8163841u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return float(h & 0xffffffu) / 16777216.0;
}

// Corner m of the cell at c: bit 0 along i, bit 1 along j, bit 2 along k
// (not along an axis of one voxel).
ivec3 corner(ivec3 c, int m, ivec3 wide)
{
    return c + ivec3(m & 1, (m >> 1) & 1, (m >> 2) & 1) * wide;
}

#ifdef RESOLVE
// The label of a sample of `value` in a cell of mixed labels: from a
// lowest and a highest corner, up the tree, the deeper first, until a
// saddle lies between (LabelTree::resolve).
int resolved_label(ivec3 c, ivec3 wide, float value)
{
    float low_value = 3.0e38, high_value = -3.0e38;
    ivec3 low_at = c, high_at = c;
    for (int m = 0; m < 8; ++m) {
        ivec3 p = corner(c, m, wide);
        float v = texelFetch(u_values, p, 0).r;
        if (v < low_value) {
            low_value = v;
            low_at = p;
        }
        if (v > high_value) {
            high_value = v;
            high_at = p;
        }
    }
    int low = int(texelFetch(u_labels, low_at, 0).r >> 1u), high = int(texelFetch(u_labels, high_at, 0).r >> 1u);
    for (int n = 0; n < 65536 && low != high; ++n) {
        vec4 l = texelFetch(u_tree, ivec2(low, 0), 0), h = texelFetch(u_tree, ivec2(high, 0), 0);
        if (h.y > l.y) {
            if (h.z <= value)
                return high;
            high = int(h.x);
        } else {
            if (l.z >= value)
                return low;
            low = int(l.x);
        }
    }
    return low;
}
#endif

#ifdef SMOOTH
// The gradient at the sample (SampleGradient): xyz its unit direction (0
// where it vanishes), w its magnitude on the 8-bit scale.
vec4 sample_gradient(ivec3 c, ivec3 wide, vec3 f)
{
    vec3 g = vec3(1.0) - f;
    vec3 sum = vec3(0.0);
    float magnitude = 0.0;
    for (int m = 0; m < 8; ++m) {
        float w = ((m & 1) != 0 ? f.x : g.x) * ((m & 2) != 0 ? f.y : g.y) * ((m & 4) != 0 ? f.z : g.z);
        ivec4 nv = texelFetch(u_normals, corner(c, m, wide), 0);
        float byte = float(nv.w + 128);
        magnitude += w * byte;
        sum += (w * (byte + 0.25)) * vec3(nv.xyz);
    }
    float len = length(sum);
    return vec4(len > 0.0 ? sum / len : vec3(0.0), magnitude);
}
#endif

// Where the ray o + t d (t >= 0) is inside the box [lo, hi]: x > y when it
// misses.
vec2 chord(vec3 o, vec3 d, vec3 lo, vec3 hi)
{
    float t0 = 0.0, t1 = 3.0e38;
    for (int a = 0; a < 3; ++a) {
        if (abs(d[a]) < 1e-12) {
            if (o[a] < lo[a] || o[a] > hi[a])
                t1 = -1.0;
            continue;
        }
        float ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
        t0 = max(t0, min(ta, tb));
        t1 = min(t1, max(ta, tb));
    }
    return vec2(t0, t1);
}

#ifdef OCCLUSION
// The visible share of the half-space around voxel position p on the side
// of unit normal n, in [0.3, 1]: short rays along the directions on that
// side, weighted by their cosine, their steps `jitter` of a step early
// (LocalOcclusion::visibility).
float occlusion_visibility(vec3 p, vec3 n, float jitter)
{
    vec3 last = vec3(max(u_dims - 2, ivec3(0))), high = vec3(u_dims - 1);
    float sum = 0.0, weight = 0.0;
    for (int d = 0; d < 14; ++d) {
        float cosine = dot(u_occlusion_world[d], n);
        if (cosine <= 0.0)
            continue;
        float transmittance = 1.0;
        for (int s = 1; s <= 4; ++s) {
            vec3 q = p + (float(s) - jitter) * u_occlusion_step[d];
            if (any(lessThan(q, vec3(0.0))) || any(greaterThan(q, high)))
                break; // beyond the field of view: nothing occludes
            ivec3 c = ivec3(min(floor(q), last));
            float value = texture(u_values, (q + 0.5) / vec3(u_dims)).r;
#ifdef LABELLED
            int label = int(texelFetch(u_labels, c, 0).r >> 1u);
#else
            int label = 0;
#endif
            vec4 range = texelFetch(u_ranges, ivec2(label, 0), 0);
            float index = clamp((value - range.x) * range.y, 0.0, range.z);
            float a = texelFetch(u_occlusion, ivec2(int(index + 0.5), label), 0).a;
#ifdef BOUNDARY
            a *= texelFetch(u_factors, ivec2(texelFetch(u_normals, c, 0).w + 128, 0), 0).r;
#endif
            transmittance *= 1.0 - a;
        }
        sum += cosine * transmittance;
        weight += cosine;
    }
    return weight > 0.0 ? max(0.3, sum / weight) : 1.0;
}
#endif

#ifdef ISOTROPIC
uniform float u_gradient_scale, u_flat_gradient; // per mm -> the 8-bit scale; flat below
uniform vec3 u_resample_scale; // per axis: its spacing over the finest on thick slices, else 1

// The plane of voxels `at` along axis a, bilinear across it at f.
float plane_value(ivec3 at, int a, ivec3 wide, vec3 f)
{
    int b = (a + 1) % 3, e = (a + 2) % 3;
    ivec3 db = ivec3(0), de = ivec3(0);
    db[b] = wide[b];
    de[e] = wide[e];
    float p00 = texelFetch(u_values, at, 0).r, p10 = texelFetch(u_values, at + db, 0).r;
    float p01 = texelFetch(u_values, at + de, 0).r, p11 = texelFetch(u_values, at + db + de, 0).r;
    return mix(mix(p00, p10, f[b]), mix(p01, p11, f[b]), f[e]);
}

// The gradient on thick slices (IsotropicGradient): the one the voxels'
// central differences give on the volume resampled to isotropic voxels at
// its finest spacing.  xyz its unit direction in mm (0 where flat), w its
// magnitude on the 8-bit scale.
vec4 isotropic_gradient(ivec3 c, ivec3 wide, vec3 f)
{
    vec3 d;
    for (int a = 0; a < 3; ++a) {
        ivec3 along = ivec3(0);
        along[a] = wide[a];
        float w0 = max(0.0, 1.0 - f[a] * u_resample_scale[a]);
        float w1 = max(0.0, 1.0 - (1.0 - f[a]) * u_resample_scale[a]);
        float p0 = plane_value(c, a, wide, f), p1 = plane_value(c + along, a, wide, f);
        float da = (1.0 - w0 - w1) * (p1 - p0);
        if (w0 > 0.0)
            da += w0 * (c[a] > 0 ? 0.5 * (p1 - plane_value(c - along, a, wide, f)) : p1 - p0);
        if (w1 > 0.0)
            da += w1 * (c[a] + 2 < u_dims[a] ? 0.5 * (plane_value(c + 2 * along, a, wide, f) - p0) : p1 - p0);
        d[a] = da;
    }
    // Index-space derivatives to LPS by the inverse transpose.
    vec3 w = transpose(u_to_voxel) * d;
    float len = length(w);
    return vec4(len > u_flat_gradient ? w / len : vec3(0.0), min(255.0, len * u_gradient_scale));
}
#endif

// The first position of the ray's lattice past the block holding cell c.
float skip_block(vec3 o, vec3 d, float t, float offset, ivec3 c)
{
    float exit = 3.0e38;
    for (int a = 0; a < 3; ++a) {
        if (abs(d[a]) < 1e-12)
            continue;
        int b = c[a] >> 3;
        float bound = d[a] > 0.0 ? float((b + 1) * 8) : float(b * 8) - 1e-4;
        exit = min(exit, (bound - o[a]) / d[a]);
    }
    return max(t + u_step, ceil((exit - offset) / u_step) * u_step + offset);
}

// What the ray has gathered (premultiplied), where it became half opaque
// (-1: not yet), per label what its samples contributed (VISIBILITY), and
// what its samples share.
vec4 g_acc;
float g_depth;
#ifdef VISIBILITY
float g_seen[32];
#endif
vec3 g_light;
float g_fraction;
ivec3 g_last, g_wide;

// The sample at voxel position x composited into the ray at distance t:
// classified by the step's tables (the refined step's when `refined`),
// opacity 1 - (1 - a)^steps, shaded (RayCaster::integrate).
#ifdef REFINE
// The label of the sample at x (as integrate takes it).
int label_at(vec3 x)
{
    x = clamp(x, vec3(0.0), vec3(u_dims - 1));
    ivec3 c = min(ivec3(x), g_last);
    uint word = texelFetch(u_labels, c, 0).r;
    if ((word & 1u) == 0u)
        return int(word >> 1u);
    return resolved_label(c, g_wide, texture(u_values, (x + 0.5) / vec3(u_dims)).r);
}

// Whether the labels of the four samples across the step around t differ
// (the CPU ray caster's labels_vary): only then is the step refined.
bool labels_vary(vec3 o, vec3 d, float t, float t0, float t1)
{
    float sub = u_step / 4.0;
    int first = -1;
    for (int m = 0; m < 4; ++m) {
        float ts = t + (float(m) - 1.5) * sub;
        if (ts < t0 || ts > t1)
            continue;
        int label = label_at(o + ts * d);
        if (first >= 0 && label != first)
            return true;
        first = label;
    }
    return false;
}
#endif

void integrate(vec3 x, float t, float steps, bool refined)
{
    x = clamp(x, vec3(0.0), vec3(u_dims - 1));
    ivec3 c = min(ivec3(x), g_last);
    vec3 f = x - vec3(c);
    float value = texture(u_values, (x + 0.5) / vec3(u_dims)).r;
    ivec3 nearest = c + ivec3(greaterThanEqual(f, vec3(0.5))) * g_wide;
#if defined(LABELLED) && defined(RESOLVE)
    uint word = texelFetch(u_labels, c, 0).r;
    int label = (word & 1u) != 0u ? resolved_label(c, g_wide, value) : int(word >> 1u);
#elif defined(LABELLED)
    int label = int(texelFetch(u_labels, nearest, 0).r >> 1u);
#else
    int label = 0;
#endif
    vec4 range = texelFetch(u_ranges, ivec2(label, 0), 0);
    ivec2 entry = ivec2(int(clamp((value - range.x) * range.y, 0.0, range.z) + 0.5), label);
    vec4 s = refined ? texelFetch(u_refined, entry, 0) : texelFetch(u_lut, entry, 0);
    if (!(s.a > 0.0))
        return;
#if defined(SHADED) || defined(BOUNDARY)
#if defined(SMOOTH) && defined(ISOTROPIC)
    vec4 gradient = isotropic_gradient(c, g_wide, f);
    vec3 n = gradient.xyz;
    float magnitude = gradient.w;
#elif defined(SMOOTH)
    vec4 gradient = sample_gradient(c, g_wide, f);
    vec3 n = gradient.xyz;
    float magnitude = gradient.w;
#else
    ivec4 nv = texelFetch(u_normals, nearest, 0);
    vec3 n = vec3(nv.xyz) / 127.0;
    float magnitude = float(nv.w + 128);
#endif
#endif
    float m = 1.0;
#ifdef BOUNDARY
    m = texelFetch(u_factors, ivec2(int(magnitude + 0.5), 0), 0).r;
#endif
    if (steps != 1.0) {
        float a = s.a * m;
        m *= a < 1.0 ? (1.0 - pow(1.0 - a, steps)) / a : 1.0;
    }
    s *= m;
    float w = 1.0 - g_acc.a;
#ifdef SHADED
    if (n != vec3(0.0)) {
        float facing = dot(n, g_light);
        float ndl = min(1.0, abs(facing));
        float spec = texelFetch(u_factors, ivec2(int(ndl * 256.0), 1), 0).r * s.a;
        float lit = u_ambient + u_diffuse * ndl;
#ifdef OCCLUSION
        if (w * s.a >= 0.01) // the side of the surface the viewer sees
            lit *= 1.0 - u_occlusion_strength * (1.0 - occlusion_visibility(x, facing >= 0.0 ? n : -n, g_fraction));
#endif
        s.rgb = s.rgb * lit + spec;
    }
#endif
    g_acc += w * s;
#ifdef VISIBILITY
    int slot = label - u_visibility_base;
    if (slot >= 0 && slot < 32)
        g_seen[slot] += w * s.a;
#endif
    if (g_acc.a >= 0.5 && g_depth < 0.0)
        g_depth = t;
}

void main()
{
    vec2 at = u_base + floor(gl_FragCoord.xy) * u_spacing;
    vec2 p = at + u_subpixel;
    float sx = (2.0 * p.x / u_frame.x - 1.0) * u_aspect * u_half;
    float sy = (1.0 - 2.0 * p.y / u_frame.y) * u_half;
    vec3 eye = u_eye, dir = u_forward;
    if (u_perspective)
        dir = normalize(u_forward + sx * u_right + sy * u_up);
    else
        eye = u_eye + sx * u_right + sy * u_up;

    vec3 o = u_to_voxel * (eye - u_origin);
    vec3 d = u_to_voxel * dir;
    vec2 content = chord(o, d, u_content_low, u_content_high);
    float t0 = content.x, t1 = content.y;
    // Entering and leaving through the volume's own faces, the first and
    // last samples stand for the part of a step up to the face.
    vec2 volume = chord(o, d, vec3(0.0), vec3(u_dims - 1));
    bool enters_face = t0 > 0.0 && abs(t0 - volume.x) < 1e-4, leaves_face = abs(t1 - volume.y) < 1e-4;

#ifdef JITTER
    float fraction = pixel_hash(uvec2(at));
    fraction = fract(fraction + u_shift);
#else
    float fraction = 0.0;
#endif
    float offset = fraction * u_step;
    float t = ceil((t0 - offset) / u_step) * u_step + offset;
    float first = t;
    g_last = max(u_dims - 2, ivec3(0));
    g_wide = ivec3(greaterThan(u_dims, ivec3(1)));
    g_light = -dir;
    g_fraction = fraction;
    g_acc = vec4(0.0);
    g_depth = -1.0;
#ifdef VISIBILITY
    for (int l = 0; l < 32; ++l)
        g_seen[l] = 0.0;
#endif
    while (t <= t1 && g_acc.a < u_termination) {
        vec3 x = o + t * d;
        ivec3 c = min(ivec3(x), g_last);
        if (texelFetch(u_blocks, c >> 3, 0).r != 0u) {
            t = skip_block(o, d, t, offset, c);
            continue;
        }
#ifdef REFINE
        // A cell where structures meet and labels differ across the step:
        // four samples across it, so a structure thinner than a step is not
        // missed between samples (not in the coarse pass).
        if ((texelFetch(u_labels, c, 0).r & 1u) != 0u && labels_vary(o, d, t, t0, t1)) {
            float sub = u_step / 4.0;
            for (int m = 0; m < 4 && g_acc.a < u_termination; ++m) {
                float ts = t + (float(m) - 1.5) * sub;
                if (ts >= t0 && ts <= t1)
                    integrate(o + ts * d, ts, 1.0, true);
            }
            t += u_step;
            continue;
        }
#endif
        // A sample stands for the step around it; at a face, for the part
        // of it inside.
        float steps = 1.0;
        if (enters_face && t == first)
            steps += (t - t0) / u_step - 0.5;
        if (leaves_face && t + u_step > t1)
            steps += (t1 - t) / u_step - 0.5;
        integrate(x, t, steps, false);
        t += u_step;
    }
#ifdef VISIBILITY
    // Outputs indexed by constants only (GLSL 3.30).
    o_visibility[0] = vec4(g_seen[0], g_seen[1], g_seen[2], g_seen[3]);
    o_visibility[1] = vec4(g_seen[4], g_seen[5], g_seen[6], g_seen[7]);
    o_visibility[2] = vec4(g_seen[8], g_seen[9], g_seen[10], g_seen[11]);
    o_visibility[3] = vec4(g_seen[12], g_seen[13], g_seen[14], g_seen[15]);
    o_visibility[4] = vec4(g_seen[16], g_seen[17], g_seen[18], g_seen[19]);
    o_visibility[5] = vec4(g_seen[20], g_seen[21], g_seen[22], g_seen[23]);
    o_visibility[6] = vec4(g_seen[24], g_seen[25], g_seen[26], g_seen[27]);
    o_visibility[7] = vec4(g_seen[28], g_seen[29], g_seen[30], g_seen[31]);
#else
    float rest = 1.0 - g_acc.a;
    o_rgba = vec4(min(vec3(1.0), g_acc.rgb + rest * u_background.rgb * u_background.a),
                  min(1.0, g_acc.a + rest * u_background.a));
    o_depth = g_depth;
#endif
}
