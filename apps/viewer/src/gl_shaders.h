// GLSL 3.30 sources of the viewer's four programs.
#pragma once

namespace lapis::viewer::shaders {

// Shaded triangles with per-vertex colour: two-sided Blinn–Phong under a head light plus a
// dim fill light, so the shape reads from any orbit angle.
inline constexpr const char* kMeshVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 color;
uniform mat4 view;
uniform mat4 projection;
out vec3 v_normal;
out vec3 v_position;
out vec3 v_color;
void main() {
  vec4 p = view * vec4(position, 1.0);
  v_position = p.xyz;
  v_normal = mat3(view) * normal;
  v_color = color;
  gl_Position = projection * p;
}
)";

inline constexpr const char* kMeshFragment = R"(#version 330 core
in vec3 v_normal;
in vec3 v_position;
in vec3 v_color;
uniform float alpha;
out vec4 frag;
void main() {
  vec3 n = normalize(v_normal);
  vec3 v = normalize(-v_position);
  if (dot(n, v) < 0.0) n = -n;
  vec3 key = normalize(vec3(0.3, 0.6, 1.0));
  vec3 fill = normalize(vec3(-0.6, -0.2, 0.5));
  float diffuse = max(dot(n, key), 0.0) * 0.75 + max(dot(n, fill), 0.0) * 0.2;
  float specular = pow(max(dot(n, normalize(key + v)), 0.0), 48.0) * 0.25;
  frag = vec4(v_color * (0.18 + diffuse) + vec3(specular), alpha);
}
)";

// Line strips. Kajiya–Kay (1989) shades a fibre by its tangent T: diffuse sin(T, L),
// specular sin(T,L)·sin(T,V) − cos(T,L)·cos(T,V) raised to a power; tips fade out.
inline constexpr const char* kLineVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 tangent;
layout(location = 2) in vec4 color;
uniform mat4 view;
uniform mat4 projection;
out vec3 v_tangent;
out vec3 v_position;
out vec4 v_color;
void main() {
  vec4 p = view * vec4(position, 1.0);
  v_position = p.xyz;
  v_tangent = mat3(view) * tangent;
  v_color = color;
  gl_Position = projection * p;
}
)";

inline constexpr const char* kLineFragment = R"(#version 330 core
in vec3 v_tangent;
in vec3 v_position;
in vec4 v_color;
uniform int kajiya_kay;
uniform float alpha;
out vec4 frag;
void main() {
  if (kajiya_kay == 0) { frag = vec4(v_color.rgb, v_color.a * alpha); return; }
  vec3 t = normalize(v_tangent);
  vec3 v = normalize(-v_position);
  vec3 l = normalize(vec3(0.3, 0.7, 0.8));
  float tl = dot(t, l), tv = dot(t, v);
  float sin_tl = sqrt(max(1.0 - tl * tl, 0.0)), sin_tv = sqrt(max(1.0 - tv * tv, 0.0));
  float diffuse = sin_tl;
  float specular = pow(max(sin_tl * sin_tv - tl * tv, 0.0), 40.0);
  vec3 c = v_color.rgb * (0.25 + 0.75 * diffuse) + vec3(0.35) * specular;
  frag = vec4(c, v_color.a * alpha);
}
)";

// Hair ribbons (LineShading::HairRibbons). The geometry shader turns each segment of a line
// strip into a quad facing the camera, `width` pixels wide at the root tapering to
// tip_width · width (at least one pixel: thinner strands fade instead of flickering). Without
// MSAA each side gets one pixel of fringe whose coverage fades linearly; with MSAA the samples
// anti-alias the edges, and a fringe would only double the fragments (software GL's cost).
// Coverage goes out as alpha, which the renderer turns into MSAA sample coverage, so ribbons
// need no sorting.
inline constexpr const char* kRibbonVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 tangent;
layout(location = 2) in vec4 color;
layout(location = 3) in vec2 along_light;  // x: fraction along the strip (0 root, 1 tip); y: light
uniform mat4 view;
uniform mat4 projection;
out VertexData { vec3 tangent; vec3 position; vec4 color; vec2 along_light; } v;
void main() {
  vec4 p = view * vec4(position, 1.0);
  v.position = p.xyz;
  v.tangent = mat3(view) * tangent;
  v.color = color;
  v.along_light = along_light;
  gl_Position = projection * p;
}
)";

inline constexpr const char* kRibbonGeometry = R"(#version 330 core
layout(lines) in;
layout(triangle_strip, max_vertices = 4) out;
in VertexData { vec3 tangent; vec3 position; vec4 color; vec2 along_light; } v[];
uniform vec2 viewport;    // pixels
uniform float width;      // pixels, at the root
uniform float tip_width;  // fraction of width at the tip
uniform float fringe;     // pixels of fading edge on each side (0 with MSAA)
out vec3 g_tangent;
out vec3 g_position;
out vec4 g_color;
out float g_light;
out float g_across;  // pixels from the centre line
out float g_half;    // the ribbon's half width there, pixels
void main() {
  vec4 c0 = gl_in[0].gl_Position, c1 = gl_in[1].gl_Position;
  if (c0.w <= 0.0 || c1.w <= 0.0) return;  // reaches behind the eye
  vec2 half_viewport = 0.5 * viewport;
  vec2 d = (c1.xy / c1.w - c0.xy / c0.w) * half_viewport;
  float len = length(d);
  vec2 dir = len > 1e-5 ? d / len : vec2(1.0, 0.0);
  vec2 n = vec2(-dir.y, dir.x);
  for (int k = 0; k < 2; ++k) {
    vec4 c = gl_in[k].gl_Position;
    float half_w = 0.5 * width * mix(1.0, tip_width, v[k].along_light.x);
    float extent = max(half_w, 0.5) + fringe;
    for (int side = -1; side <= 1; side += 2) {
      vec2 offset = n * (float(side) * extent) / half_viewport;
      gl_Position = vec4(c.xy + offset * c.w, c.z, c.w);
      g_tangent = v[k].tangent;
      g_position = v[k].position;
      g_color = v[k].color;
      g_light = v[k].along_light.y;
      g_across = float(side) * extent;
      g_half = half_w;
      EmitVertex();
    }
  }
  EndPrimitive();
}
)";

inline constexpr const char* kRibbonFragment = R"(#version 330 core
in vec3 g_tangent;
in vec3 g_position;
in vec4 g_color;
in float g_light;
in float g_across;
in float g_half;
uniform float alpha;
uniform float fringe;
out vec4 frag;
// Kajiya–Kay's specular lobe: brightest where the view lies on the cone of mirror directions
// around the tangent.
float kajiya_kay(vec3 t, vec3 l, vec3 v, float power) {
  float tl = dot(t, l), tv = dot(t, v);
  float s = sqrt(max(1.0 - tl * tl, 0.0)) * sqrt(max(1.0 - tv * tv, 0.0)) - tl * tv;
  return pow(max(s, 0.0), power);
}
void main() {
  // Coverage of this pixel by a ribbon of half width g_half: 1 inside, a linear ramp over the
  // fringe (if any), scaled down for ribbons thinner than a pixel.
  float edge = fringe > 0.0 ? clamp(max(g_half, 0.5) + 0.5 * fringe - abs(g_across), 0.0, fringe) / fringe : 1.0;
  float coverage = edge * min(2.0 * g_half, 1.0);
  if (coverage <= 0.0) discard;
  vec3 t = normalize(g_tangent);
  vec3 v = normalize(-g_position);
  vec3 n = v - dot(v, t) * t;  // the fibre's normal toward the eye
  n = length(n) > 1e-4 ? normalize(n) : vec3(0.0, 0.0, 1.0);
  vec3 l = normalize(vec3(0.3, 0.7, 0.8));
  float tl = dot(t, l);
  float diffuse = sqrt(max(1.0 - tl * tl, 0.0));
  // The cuticle's scales tilt the fibre's surface: the white highlight (reflection) moves toward
  // the root and the coloured one (light through the fibre and back) toward the tip.
  float primary = kajiya_kay(normalize(t - 0.12 * n), l, v, 90.0);
  float secondary = kajiya_kay(normalize(t + 0.18 * n), l, v, 24.0);
  vec3 base = g_color.rgb;
  float ambient = 0.25 * (0.4 + 0.6 * g_light);
  vec3 c = base * (ambient + 0.80 * diffuse * g_light) +
           g_light * (vec3(0.40) * primary + 0.6 * base * secondary);
  frag = vec4(c, coverage * g_color.a * alpha);
}
)";

inline constexpr const char* kPointVertex = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 color;
uniform mat4 view;
uniform mat4 projection;
uniform float size;
out vec3 v_color;
void main() {
  v_color = color;
  gl_Position = projection * view * vec4(position, 1.0);
  gl_PointSize = size;
}
)";

inline constexpr const char* kPointFragment = R"(#version 330 core
in vec3 v_color;
out vec4 frag;
void main() {
  vec2 d = gl_PointCoord - vec2(0.5);
  if (dot(d, d) > 0.25) discard;
  frag = vec4(v_color, 1.0);
}
)";

}  // namespace lapis::viewer::shaders
