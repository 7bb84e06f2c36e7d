// present.frag - the rays one pass cast (u_rays, what raycast.frag wrote)
// into the host's frame texture (arbor.renderer-gl/1): a fragment is frame
// pixel gl_FragCoord.xy - 0.5, row 0 the top row.  Full and supersample
// passes cast a ray per pixel of the region; the coarse pass a lattice of
// rays, and a pixel takes the bilinear mix of the four around it, as the
// CPU ray caster's coarse pass does (plugins/raycast/coarse_lattice.cpp).
// A supersample pass blends with the constant blend colour.

uniform sampler2D u_rays;    // RGBA32F, ray (i, j) at texel (i, j)
uniform ivec2 u_ray_count;   // rays cast across and down
uniform vec2 u_region;       // frame pixel of ray (0, 0) when a ray is cast per pixel
uniform bool u_coarse;
uniform vec2 u_lattice_base; // coarse: frame position of ray (0, 0)
uniform float u_spacing;     // coarse: frame pixels between neighbouring rays
uniform bool u_clamp;        // full and coarse: colour clamped to [0, 1]

out vec4 o_rgba;

void main()
{
    vec4 c;
    if (u_coarse) {
        vec2 s = clamp((gl_FragCoord.xy - u_lattice_base) / u_spacing, vec2(0.0), vec2(u_ray_count - 1));
        ivec2 a = min(ivec2(s), u_ray_count - 1);
        ivec2 b = min(a + 1, u_ray_count - 1);
        vec2 f = s - vec2(a);
        vec4 top = mix(texelFetch(u_rays, a, 0), texelFetch(u_rays, ivec2(b.x, a.y), 0), f.x);
        vec4 bottom = mix(texelFetch(u_rays, ivec2(a.x, b.y), 0), texelFetch(u_rays, b, 0), f.x);
        c = mix(top, bottom, f.y);
    } else {
        c = texelFetch(u_rays, ivec2(gl_FragCoord.xy - u_region), 0);
    }
    o_rgba = u_clamp ? clamp(c, 0.0, 1.0) : c;
}
