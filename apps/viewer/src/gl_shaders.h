// GLSL 3.30 sources of the viewer's three programs.
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
