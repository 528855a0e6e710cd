// OpenGL 3.3 core renderer of a Scene. Buffers are cached per item name and re-uploaded
// only when the item's version changes; all strips of a LineItem go out in one draw call
// (primitive restart), so 20K strands cost one call, not 20K; and an unchanged scene is not
// drawn again but copied from the last picture (frame_cache.h).
#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "frame_cache.h"
#include "gl_program.h"
#include "gl_shaders.h"
#include "lapis/core/error.h"
#include "lapis/geometry/normals.h"
#include "lapis/viewer/renderer.h"

namespace lapis::viewer {
namespace {

constexpr GLuint kRestart = 0xFFFFFFFFu;

// One vertex array with its buffers.
struct GpuItem {
  GLuint vao = 0, ibo = 0;
  GLuint vbo[4] = {0, 0, 0, 0};
  GLsizei count = 0;
  std::uint64_t version = ~0ull;

  void create() {
    if (vao) return;
    glGenVertexArrays(1, &vao);
    glGenBuffers(4, vbo);
    glGenBuffers(1, &ibo);
  }
  void destroy() {
    if (!vao) return;
    glDeleteBuffers(4, vbo);
    glDeleteBuffers(1, &ibo);
    glDeleteVertexArrays(1, &vao);
    vao = 0;
  }
  void attribute(int slot, const float* data, size_t floats, int components) {
    glBindBuffer(GL_ARRAY_BUFFER, vbo[slot]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(floats * sizeof(float)), data, GL_STATIC_DRAW);
    glEnableVertexAttribArray(static_cast<GLuint>(slot));
    glVertexAttribPointer(static_cast<GLuint>(slot), components, GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  void indices(const std::vector<GLuint>& idx) {
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(idx.size() * sizeof(GLuint)), idx.data(),
                 GL_STATIC_DRAW);
    count = static_cast<GLsizei>(idx.size());
  }
};

class GlRenderer final : public Renderer {
 public:
  explicit GlRenderer(bool frame_cache)
      : use_cache_(frame_cache),
        mesh_program_(link_program(shaders::kMeshVertex, shaders::kMeshFragment)),
        line_program_(link_program(shaders::kLineVertex, shaders::kLineFragment)),
        ribbon_program_(link_program(shaders::kRibbonVertex, shaders::kRibbonGeometry, shaders::kRibbonFragment)),
        point_program_(link_program(shaders::kPointVertex, shaders::kPointFragment)) {}

  ~GlRenderer() override {
    for (auto* cache : {&meshes_, &lines_, &points_})
      for (auto& [name, item] : *cache) item.destroy();
    glDeleteProgram(mesh_program_);
    glDeleteProgram(line_program_);
    glDeleteProgram(ribbon_program_);
    glDeleteProgram(point_program_);
  }

  RenderStats stats() const override { return stats_; }

  void render_uncached(const Scene& scene, const geometry::CameraMatrices& camera, int width, int height,
                       float pixel_scale) override {
    stats_ = {};
    pixel_scale_ = pixel_scale;
    draw_scene(scene, camera, width, height);
    pixel_scale_ = 1.0f;
  }

  void render(const Scene& scene, const geometry::CameraMatrices& camera, int width, int height) override {
    const std::uint64_t signature = scene_signature(scene, camera, width, height);
    if (use_cache_ && cache_.draw(signature, width, height)) {
      stats_ = {true, 0, 0, 0};
      return;
    }
    stats_ = {};
    pixel_scale_ = 1.0f;
    draw_scene(scene, camera, width, height);
    // Stored unless the camera moves: storing resolves the MSAA buffer, which a frame of an
    // orbit (a new picture every frame) would pay for nothing. With the camera still, the
    // frames that follow a change (the few drawn after any input, those while a worker runs)
    // then cost a copy, not another full drawing, and a worker's result does not wait for one.
    const std::uint64_t view = camera_signature(camera, width, height);
    if (use_cache_ && (signature == last_signature_ || view == last_view_)) cache_.store(signature, width, height);
    last_signature_ = signature;
    last_view_ = view;
  }

 private:
  void draw_scene(const Scene& scene, const geometry::CameraMatrices& camera, int width, int height) {
    glViewport(0, 0, width, height);
    glClearColor(scene.background.x(), scene.background.y(), scene.background.z(), 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_MULTISAMPLE);
    glEnable(GL_PRIMITIVE_RESTART);
    glPrimitiveRestartIndex(kRestart);
    glEnable(GL_PROGRAM_POINT_SIZE);
    const Eigen::Matrix4f view = camera.view.cast<float>(), proj = camera.projection.cast<float>();

    // Opaque meshes, then lines (strands blend over the head), then translucent meshes
    // (supporting surfaces), then on-top overlays.
    glDisable(GL_BLEND);
    for (const auto& [name, m] : scene.meshes)
      if (m.visible && m.alpha >= 1.0f) draw_mesh(name, m, view, proj);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    for (const auto& [name, l] : scene.lines)
      if (l.visible && !l.on_top) draw_lines(name, l, view, proj);
    glDepthMask(GL_FALSE);
    for (const auto& [name, m] : scene.meshes)
      if (m.visible && m.alpha < 1.0f) draw_mesh(name, m, view, proj);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    for (const auto& [name, l] : scene.lines)
      if (l.visible && l.on_top) draw_lines(name, l, view, proj);
    for (const auto& [name, p] : scene.points)
      if (p.visible) draw_points(name, p, view, proj);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    forget_removed(scene);
  }

  static void set_camera(GLuint program, const Eigen::Matrix4f& view, const Eigen::Matrix4f& proj) {
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "view"), 1, GL_FALSE, view.data());
    glUniformMatrix4fv(glGetUniformLocation(program, "projection"), 1, GL_FALSE, proj.data());
  }

  void draw_mesh(const std::string& name, const MeshItem& m, const Eigen::Matrix4f& view, const Eigen::Matrix4f& proj) {
    GpuItem& g = meshes_[name];
    if (g.version != m.version) upload_mesh(g, m);
    if (!g.count) return;
    stats_.triangles += g.count / 3;
    set_camera(mesh_program_, view, proj);
    glUniform1f(glGetUniformLocation(mesh_program_, "alpha"), m.alpha);
    glBindVertexArray(g.vao);
    glDrawElements(GL_TRIANGLES, g.count, GL_UNSIGNED_INT, nullptr);
  }

  static void upload_mesh(GpuItem& g, const MeshItem& m) {
    g.create();
    glBindVertexArray(g.vao);
    const Points3f V = m.mesh.V.cast<float>();
    const Points3f N =
        m.mesh.F.rows() ? Points3f(geometry::vertex_normals(m.mesh).cast<float>()) : Points3f(V.rows(), 3);
    Points3f C = m.colors;
    if (C.rows() != V.rows()) C = m.base_color.transpose().replicate(V.rows(), 1);
    g.attribute(0, V.data(), static_cast<size_t>(V.size()), 3);
    g.attribute(1, N.data(), static_cast<size_t>(N.size()), 3);
    g.attribute(2, C.data(), static_cast<size_t>(C.size()), 3);
    std::vector<GLuint> idx(static_cast<size_t>(m.mesh.F.size()));
    for (Eigen::Index k = 0; k < m.mesh.F.size(); ++k)
      idx[static_cast<size_t>(k)] = static_cast<GLuint>(m.mesh.F.data()[k]);
    g.indices(idx);
    g.version = m.version;
  }

  void draw_lines(const std::string& name, const LineItem& l, const Eigen::Matrix4f& view,
                  const Eigen::Matrix4f& proj) {
    GpuItem& g = lines_[name];
    if (g.version != l.version) upload_lines(g, l);
    if (!g.count) return;
    stats_.strips += l.num_strips();
    if (l.shading == LineShading::HairRibbons) return draw_ribbons(g, l, view, proj);
    set_camera(line_program_, view, proj);
    glUniform1i(glGetUniformLocation(line_program_, "kajiya_kay"), l.shading == LineShading::KajiyaKay);
    glUniform1f(glGetUniformLocation(line_program_, "alpha"), l.alpha);
    glLineWidth(l.width * pixel_scale_);
    glBindVertexArray(g.vao);
    glDrawElements(GL_LINE_STRIP, g.count, GL_UNSIGNED_INT, nullptr);
  }

  // Ribbons write depth and turn their edge coverage into MSAA sample coverage, which needs
  // no back-to-front order; without MSAA they blend instead (order-dependent at the edges).
  void draw_ribbons(const GpuItem& g, const LineItem& l, const Eigen::Matrix4f& view, const Eigen::Matrix4f& proj) {
    GLint viewport[4], samples = 0;
    glGetIntegerv(GL_VIEWPORT, viewport);
    glGetIntegerv(GL_SAMPLES, &samples);
    set_camera(ribbon_program_, view, proj);
    glUniform2f(glGetUniformLocation(ribbon_program_, "viewport"), static_cast<float>(viewport[2]),
                static_cast<float>(viewport[3]));
    glUniform1f(glGetUniformLocation(ribbon_program_, "width"), l.width * pixel_scale_);
    glUniform1f(glGetUniformLocation(ribbon_program_, "tip_width"), l.tip_width);
    glUniform1f(glGetUniformLocation(ribbon_program_, "alpha"), l.alpha);
    glUniform1f(glGetUniformLocation(ribbon_program_, "fringe"), samples > 0 ? 0.0f : 1.0f);
    if (samples > 0) {
      glDisable(GL_BLEND);
      glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    }
    glBindVertexArray(g.vao);
    glDrawElements(GL_LINE_STRIP, g.count, GL_UNSIGNED_INT, nullptr);
    if (samples > 0) {
      glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
      glEnable(GL_BLEND);
    }
  }

  static void upload_lines(GpuItem& g, const LineItem& l) {
    g.create();
    glBindVertexArray(g.vao);
    const Eigen::Index n = l.points.rows();
    Points3f T(n, 3);
    Eigen::Matrix<float, Eigen::Dynamic, 4, Eigen::RowMajor> C(n, 4);
    Eigen::Matrix<float, Eigen::Dynamic, 2, Eigen::RowMajor> along_light(n, 2);  // ribbons' taper and light
    const bool has_light = l.light.size() == static_cast<size_t>(n);
    std::vector<GLuint> idx;
    idx.reserve(static_cast<size_t>(n + l.num_strips()));
    for (int s = 0; s < l.num_strips(); ++s) {
      const int a = l.strip_offsets[static_cast<size_t>(s)], b = l.strip_offsets[static_cast<size_t>(s) + 1];
      for (int i = a; i < b; ++i) {
        // Central differences; one-sided at the ends.
        const int i0 = std::max(a, i - 1), i1 = std::min(b - 1, i + 1);
        float t[3], len2 = 0;
        for (int k = 0; k < 3; ++k) t[k] = l.points(i1, k) - l.points(i0, k), len2 += t[k] * t[k];
        const float inv = len2 > 0 ? 1.0f / std::sqrt(len2) : 0.0f;
        for (int k = 0; k < 3; ++k) {
          T(i, k) = len2 > 0 ? t[k] * inv : (k == 1 ? 1.0f : 0.0f);
          C(i, k) = l.colors.rows() == n ? l.colors(i, k) : l.base_color[k];
        }
        C(i, 3) = 1.0f;
        along_light(i, 0) = b - a > 1 ? static_cast<float>(i - a) / static_cast<float>(b - a - 1) : 0.0f;
        along_light(i, 1) = has_light ? l.light[static_cast<size_t>(i)] : 1.0f;
        idx.push_back(static_cast<GLuint>(i));
      }
      idx.push_back(kRestart);
    }
    g.attribute(0, l.points.data(), static_cast<size_t>(l.points.size()), 3);
    g.attribute(1, T.data(), static_cast<size_t>(T.size()), 3);
    g.attribute(2, C.data(), static_cast<size_t>(C.size()), 4);
    g.attribute(3, along_light.data(), static_cast<size_t>(along_light.size()), 2);
    g.indices(idx);
    g.version = l.version;
  }

  void draw_points(const std::string& name, const PointItem& p, const Eigen::Matrix4f& view,
                   const Eigen::Matrix4f& proj) {
    GpuItem& g = points_[name];
    if (g.version != p.version) {
      g.create();
      glBindVertexArray(g.vao);
      Points3f C = p.colors;
      if (C.rows() != p.points.rows()) C = p.base_color.transpose().replicate(p.points.rows(), 1);
      g.attribute(0, p.points.data(), static_cast<size_t>(p.points.size()), 3);
      g.attribute(1, C.data(), static_cast<size_t>(C.size()), 3);
      std::vector<GLuint> idx(static_cast<size_t>(p.points.rows()));
      for (size_t i = 0; i < idx.size(); ++i) idx[i] = static_cast<GLuint>(i);
      g.indices(idx);
      g.version = p.version;
    }
    if (!g.count) return;
    stats_.points += g.count;
    set_camera(point_program_, view, proj);
    glUniform1f(glGetUniformLocation(point_program_, "size"), p.size * pixel_scale_);
    glBindVertexArray(g.vao);
    glDrawElements(GL_POINTS, g.count, GL_UNSIGNED_INT, nullptr);
  }

  // Frees the buffers of items the scene no longer has.
  template <class Map, class Cache>
  static void forget(const Map& items, Cache& cache) {
    for (auto it = cache.begin(); it != cache.end();) {
      if (!items.count(it->first)) {
        it->second.destroy();
        it = cache.erase(it);
      } else {
        ++it;
      }
    }
  }
  void forget_removed(const Scene& scene) {
    forget(scene.meshes, meshes_);
    forget(scene.lines, lines_);
    forget(scene.points, points_);
  }

  bool use_cache_;
  GLuint mesh_program_, line_program_, ribbon_program_, point_program_;
  float pixel_scale_ = 1.0f;  // widths and sizes in pixels are multiplied by it (supersampled pictures)
  std::unordered_map<std::string, GpuItem> meshes_, lines_, points_;
  FrameCache cache_;
  std::uint64_t last_signature_ = 0, last_view_ = 0;
  RenderStats stats_;
};

}  // namespace

std::unique_ptr<Renderer> make_gl_renderer(bool frame_cache) { return std::make_unique<GlRenderer>(frame_cache); }

}  // namespace lapis::viewer
