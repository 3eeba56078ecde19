// The renderer: one render pass at a time. Draws are shaded and set up as they arrive, binned into 64x64 tiles
// in API order, and rendered tile-parallel when the pass ends (or when the scene grows too large).
//
//   Renderer r(pool);
//   r.begin(framebuffer);
//   r.draw(pipeline, call, bindings);   // vertex stage, primitive assembly, clipping, setup, binning
//   r.end();                             // tiles -> fragment stage -> targets
#pragma once

#include <atomic>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rast/core/method.h"
#include "rast/core/scene.h"
#include "rast/core/thread_pool.h"
#include "rast/fragment/linear.h"
#include "rast/geometry/clip.h"
#include "rast/geometry/draw_module.h"
#include "rast/geometry/planes.h"
#include "rast/render/draw_state.h"
#include "rast/render/scene_records.h"
#include "rast/render/targets.h"

namespace tilevk::rast::render {

class FragmentStage;

class Renderer {
  public:
    explicit Renderer(ThreadPool& pool, Method method = method_from_env());
    ~Renderer();

    void begin(const Framebuffer& fb);
    // Returns an empty string on success, else why the draw could not be rendered (nothing was drawn).
    std::string draw(const PipelineState& pipe, const DrawCall& call, const shader::Bindings& bindings);
    // Renders what is binned. With `resolves` (the pass's last scene), also resolves them tile by tile (targets.h
    // TileResolve) and returns true; false if the scene had nothing to render (the caller resolves, nothing was
    // written).
    bool end(const TileResolves* resolves = nullptr);

    // Whether lavapipe's viewport/interpolation fmuladds are fused (host FMA) — one decision for the process.
    static bool fused();

    // Shader runs (vertex and fragment) that the loop watchdog cut short since this renderer was made. A non-zero
    // increase means some shader did not terminate: its outputs are incomplete and the driver must say so.
    uint64_t shader_loop_limit_hits() const;

    // The driver's time limit: once *stop is true, draws are dropped, the scene's remaining primitives and blocks
    // are skipped and shader runs end at their next loop back edge (the loop-count watchdog is then off), so the
    // pass ends soon after; what was drawn is undefined (the driver reports the device lost). Null: never stop.
    void set_stop_flag(const std::atomic<bool>* stop);
    // The DrawCall::id of the draw the stop interrupted since reset_interruption(): one whose shader run was cut
    // short if any, else one whose work was skipped; nullopt if the stop interrupted nothing.
    std::optional<uint32_t> interrupted_draw() const;
    void reset_interruption();

    // lavapipe bins a query command (begin/end, timestamp) into every tile of its current scene, so no bin of that
    // scene is linear-only (lp_setup.c lp_setup_begin_query / lp_setup_end_query): the icd calls this for a query
    // command inside a render pass. Applies to the scene being built (until the next begin() or flush()).
    void mark_scene_not_linear();

  private:
    void flush();
    bool render_scene(const TileResolves* resolves = nullptr);
    // A draw that alone fills a scene: renders what is binned and goes on in a fresh scene with its record, now
    // draw 0 (memory stays bounded, and a lost device is noticed between instances, not after a huge binning).
    void flush_within_draw(uint32_t* draw_index, const DrawRecord& rec);
    void reset_linear_tiles();
    void unique_vertices(size_t n);
    // Renderer::draw's jobs (renderer.cpp).
    struct DrawPlan;
    bool plan_draw(DrawPlan& plan, const PipelineState& pipe, const DrawCall& call, DrawRecord& rec,
                   const geometry::IndexSource& src);
    void draw_triangles_parallel(const DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec, bool any_clipped,
                                 uint32_t num_prims);
    // Batch [first_prim, end_prim), its primitives from start_prim on (start_prim > first_prim only in a batch
    // through draw's pipeline whose head the parallel path set up).
    void emit_batch(DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec, uint32_t first_prim, uint32_t end_prim,
                    uint32_t start_prim, bool any_clipped);
    void emit_clipped_triangle(DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec, const uint32_t* ids,
                               uint64_t batch_serial);
    void emit_unfilled(DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec, const geometry::ClippedTriangle& tri,
                       const uint64_t ids[3]);
    void emit_line(DrawPlan& plan, uint32_t draw_index, const DrawRecord& rec, const uint32_t* ids, bool pipeline_path,
                   uint64_t batch_serial);
    void record_draw(DrawRecord& rec, const PipelineState& pipe, const DrawCall& call,
                     const shader::Bindings& bindings);
    // The draw module's calls for one batch (rast/geometry/draw_module.h; renderer_emit.cpp): its SetupSink, the
    // batch as it reads it, the direct batch's rectangle pairs, the 9-vertex analysis (returns where the caller's
    // triangle loop ends) and the vbuf stage.
    class Setup;
    geometry::TriangleBatch triangle_batch(uint32_t first_prim, uint32_t end_prim) const;
    bool emit_direct_pairs(uint32_t draw_index, const DrawRecord& rec, geometry::Topology topology, bool indexed,
                           uint32_t first_prim, uint32_t end_prim);
    uint32_t nine_vertex_batch_end(uint32_t draw_index, const DrawRecord& rec, uint32_t first_prim, uint32_t end_prim);
    void vbuf_primitive(uint32_t draw, const DrawRecord& rec, const float* const* v, const uint64_t* ids,
                        float point_size = 1.0f, bool front = true);
    void vbuf_flush(uint32_t draw, const DrawRecord& rec, bool after_draw = false);

    void add_triangle(uint32_t draw, const DrawRecord& rec, const float* v0, const float* v1, const float* v2);
    // Triangles prim_slots[3*i .. 3*i+2] (shaded record slots), i in [0, n), as the primitive loop of draw()
    // treats them one after the other (pipeline[i]: the triangle's batch went through draw's pipeline: clipper,
    // float cull), set up on the workers and binned by tile bands in API order.
    struct TrianglePipeline {
        const uint8_t* pipeline;
        const geometry::ClipConfig* clip;
        const geometry::FloatCull* float_cull;
        bool any_cull;
    };
    void add_triangles_parallel(uint32_t draw, const DrawRecord& rec, const uint32_t* prim_slots, uint32_t n,
                                const TrianglePipeline& cfg);
    void add_line(uint32_t draw, const DrawRecord& rec, const float* v0, const float* v1, bool front_facing = true);
    void add_point(uint32_t draw, const DrawRecord& rec, const float* v, float size, bool front_facing = true);
    // llvmpipe's rectangle (lp_setup_rect.c try_rect_cw): box of the snapped corners, planes from (c0, c1, c2).
    void add_rect(uint32_t draw, const DrawRecord& rec, const float* c0, const float* c1, const float* c2, bool front);
    bool batch_takes_pipeline(uint32_t first, uint32_t end, bool any_clipped) const;
    uint32_t parallel_prefix(const DrawPlan& plan, bool any_clipped) const;
    // The last triangle at or after tail_first (a batch start after which every batch of the instance goes through
    // draw's pipeline) where a filling of draw's vbuf starts, no later than its last filling: a serial count of the
    // vertices the vbuf stage receives from triangles [tail_first, num_prims) (cfg.pipeline unused).
    uint32_t last_filling_start(const TrianglePipeline& cfg, uint32_t num_prims, uint32_t tail_first);
    ClipRect prim_clip(const PipelineState& pipe) const;
    // Linear mode: tiles a non-rectangle primitive may be binned to cannot be llvmpipe linear bins.
    void mark_not_linear(int32_t px0, int32_t py0, int32_t px1, int32_t py1, const ClipRect& clip);
    geometry::DepthBias depth_bias_for_target(const PipelineState& pipe) const;
    geometry::PlaneSetupConfig plane_setup_config(const DrawRecord& rec) const;
    // Appends a primitive record (position plane, depth offset, attrib_planes_[0, num_attribs)); returns its payload.
    uint32_t push_prim(uint32_t draw, PrimKind kind, const geometry::AttribPlane& pos, float depth_offset,
                       uint32_t num_attribs);

    bool stopped() const { return stop_ != nullptr && stop_->load(std::memory_order_relaxed); }

    ThreadPool& pool_;
    Method method_;
    const std::atomic<bool>* stop_ = nullptr;
    Interruption interruption_;
    Framebuffer fb_;
    std::unique_ptr<Scene> scene_;
    DrawRecords draws_;
    PrimStore prims_;  // the scene's primitive records; a primitive's payload names its record
    std::unique_ptr<FragmentStage> fragment_;
    std::vector<std::unique_ptr<VertexWorker>> vertex_workers_;  // per worker
    // Per-draw temporaries, kept to reuse their memory.
    std::vector<uint32_t> assembled_, unique_, slot_of_;
    ShadedVertices shaded_;
    std::vector<float> clip_scratch_;
    std::vector<std::vector<float>> clip_workers_;  // clip scratch per worker (add_triangles_parallel)
    std::vector<uint8_t> tri_pipeline_;             // per triangle of a parallel draw: its batch took draw's pipeline
    std::vector<uint32_t> piece_first_;             // per triangle of a parallel draw: its first slot
    std::vector<uint32_t> vbuf_stamp_;              // per shaded slot: last_filling_start's buffer generation
    std::vector<geometry::AttribPlane> attrib_planes_;
    std::vector<uint32_t> batches_;        // primitives per draw-module batch (geometry/draw_batches.h)
    std::vector<float> unfilled_scratch_;  // 3 records: a polygonMode LINE/POINT triangle after offset/flatshade
    geometry::DrawModule draw_module_;     // vbuf stage, rectangle pairs, 9-vertex analysis of the current draw
    bool vbuf_triangles_ = false;          // filled triangles: clipped batches reach setup through the vbuf
    std::vector<uint8_t> tile_linear_;                // per 64x64 tile, row-major (linear mode)
    std::vector<fragment::LinearRegion> rect_boxes_;  // pixel box of each kRect (linear mode)
};

}  // namespace tilevk::rast::render
