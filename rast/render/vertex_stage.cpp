// Vertex stage: attribute fetch -> vertex shader (SoA, 16 lanes) -> clip mask and viewport per vertex.
#include "rast/render/vertex_stage.h"

#include <algorithm>
#include <cstring>

#include "rast/geometry/fp_env.h"
#include "rast/geometry/viewport.h"

namespace tilevk::rast::render {
namespace {

float as_float(uint32_t bits) {
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

// One attribute's fetch for the draw: its shader location and its plan (rast/geometry/vertex_fetch.h).
struct AttribFetch {
    uint32_t loc = 0;
    bool bound = false;  // a binding without a buffer description reads (0, 0, 0, 0)
    geometry::AttribFetchPlan plan;
    geometry::ElementIndex instance_element{0, true};  // per-instance rate: the element of this instance
};

// The attribute fetches of one draw (at most one per shader input location).
struct Fetches {
    AttribFetch f[shader::kMaxLocations];
    uint32_t count = 0;
    const AttribFetch* begin() const { return f; }
    const AttribFetch* end() const { return f + count; }
};

void make_fetches(const VertexStageConfig& cfg, Fetches& out) {
    const VertexInputState& in = *cfg.input;
    out.count = 0;
    for (size_t a = 0; a < in.attribs.size() && out.count < shader::kMaxLocations; ++a) {
        const geometry::VertexAttribDesc& desc = in.attribs[a];
        if (in.locations[a] >= shader::kMaxLocations) continue;
        AttribFetch f;
        f.loc = in.locations[a];
        f.bound = desc.binding < in.buffers.size();
        if (f.bound) {
            const geometry::VertexBufferView& vb = in.buffers[desc.binding];
            f.plan = geometry::make_attrib_fetch_plan(desc, vb);
            f.instance_element = geometry::element_index(vb, 0, cfg.instance, cfg.first_instance);
        }
        out.f[out.count++] = f;
    }
}

void fetch_batch(const VertexStageConfig& cfg, const Fetches& fetches, const uint32_t* idx, uint32_t count,
                 shader::VertexBatch& batch) {
    for (uint32_t lane = 0; lane < count; ++lane) {
        batch.vertex_index[lane] = idx[lane];
        batch.instance_index[lane] = cfg.first_instance + cfg.instance;
    }
    // element_index per rate: the vertex index itself (always valid), or the instance's element for every lane.
    bool valid[shader::kLanes];
    for (uint32_t lane = 0; lane < count; ++lane) valid[lane] = true;
    for (const AttribFetch& f : fetches) {
        if (!f.bound) {
            for (int c = 0; c < 4; ++c)
                for (uint32_t lane = 0; lane < count; ++lane) batch.inputs[f.loc][c][lane] = 0;
            continue;
        }
        if (f.plan.per_instance) {
            uint32_t elem[shader::kLanes];
            bool inst_valid[shader::kLanes];
            for (uint32_t lane = 0; lane < count; ++lane) {
                elem[lane] = f.instance_element.index;
                inst_valid[lane] = f.instance_element.valid;
            }
            geometry::fetch_lanes(f.plan, elem, inst_valid, count, batch.inputs[f.loc]);
        } else {
            geometry::fetch_lanes(f.plan, idx, valid, count, batch.inputs[f.loc]);
        }
    }
}

// The combined ClipDistance/CullDistance array of one shaded vertex into its record (VaryingMap::distance_slot),
// zeros after the last element, and the user planes' clip-mask bits.
void store_distances(const VaryingMap& v, const shader::VertexBatch& batch, uint32_t lane, float* rec,
                     uint32_t* clipmask) {
    float* d = rec + geometry::kAttribOffset + 4 * static_cast<uint32_t>(v.distance_slot);
    const uint32_t n = v.num_clip_distances + v.num_cull_distances;
    for (uint32_t i = 0; i < (n + 3) / 4 * 4; ++i) {
        if (i < v.num_clip_distances)
            d[i] = as_float(batch.clip_distance[i][lane]);
        else if (i < n)
            d[i] = as_float(batch.cull_distance[i - v.num_clip_distances][lane]);
        else
            d[i] = 0.0f;
    }
    *clipmask |= geometry::clip_distance_mask(d, v.num_clip_distances);
}

// Vertices [first, end) of `indices` (first a multiple of kLanes) into `out`, already sized.
void shade_range(const VertexStageConfig& cfg, const Fetches& fetches, std::span<const uint32_t> indices,
                 uint32_t first_vertex, uint32_t end, VertexWorker& worker, ShadedVertices* out) {
    const uint32_t stride = out->floats_per_vertex;
    const bool writes_point_size = cfg.program->interface().builtins_written & shader::bit(shader::BuiltIn::PointSize);
    const uint32_t num_inputs = static_cast<uint32_t>(cfg.varyings->slot_location.size());
    shader::VertexBatch& batch = worker.batch;
    batch.base_vertex = cfg.base_vertex;
    batch.base_instance = cfg.first_instance;
    batch.draw_index = cfg.draw_index;
    batch.view_index = cfg.view_index;
    for (uint32_t first = first_vertex; first < end; first += shader::kLanes) {
        if (cfg.stop != nullptr && cfg.stop->load(std::memory_order_relaxed)) return;
        const uint32_t count = std::min<uint32_t>(shader::kLanes, end - first);
        batch.count = count;
        fetch_batch(cfg, fetches, indices.data() + first, count, batch);
        cfg.program->run_vertex(*cfg.bindings, batch, worker.scratch);
        for (uint32_t lane = 0; lane < count; ++lane) {
            float* rec = out->records.data() + size_t(first + lane) * stride;
            for (int c = 0; c < 4; ++c) rec[geometry::kClipPosOffset + c] = as_float(batch.position[c][lane]);
            for (uint32_t s = 0; s < num_inputs; ++s) {
                const uint32_t loc = cfg.varyings->slot_location[s];
                for (int c = 0; c < 4; ++c)
                    rec[geometry::kAttribOffset + 4 * s + c] = as_float(batch.outputs[loc][c][lane]);
            }
            out->clipmask[first + lane] = geometry::compute_clipmask(cfg.clip, rec + geometry::kClipPosOffset);
            if (cfg.varyings->distance_slot >= 0)
                store_distances(*cfg.varyings, batch, lane, rec, &out->clipmask[first + lane]);
            geometry::viewport_transform(cfg.viewport, rec + geometry::kClipPosOffset, rec + geometry::kWinPosOffset);
            out->point_size[first + lane] = writes_point_size ? as_float(batch.point_size[lane]) : 1.0f;
            if (cfg.varyings->carry_point_size) {
                float* ps = rec + geometry::kAttribOffset + 4 * num_inputs;
                ps[0] = out->point_size[first + lane];
                ps[1] = ps[2] = ps[3] = 0.0f;
            }
            if (cfg.varyings->point_coord_slot >= 0) {
                float* pc = rec + geometry::kAttribOffset + 4 * cfg.varyings->point_coord_slot;
                pc[0] = pc[1] = pc[2] = pc[3] = 0.0f;
            }
        }
    }
}

bool writes_memory(const shader::Program& p) {
    if (p.interface().writes_device_addresses) return true;
    for (const shader::DescriptorUse& d : p.interface().descriptors)
        if (d.written) return true;
    return false;
}

}  // namespace

void shade_vertices(const VertexStageConfig& cfg, std::span<const uint32_t> indices, ThreadPool& pool,
                    std::span<const std::unique_ptr<VertexWorker>> workers, ShadedVertices* out) {
    const geometry::VertexLayout layout = cfg.varyings->layout();
    const uint32_t n = static_cast<uint32_t>(indices.size());
    out->floats_per_vertex = geometry::vertex_floats(layout);
    out->records.resize(size_t(n) * out->floats_per_vertex);
    out->clipmask.resize(n);
    out->point_size.resize(n);
    Fetches fetches;
    make_fetches(cfg, fetches);
    // Chunks of 64 batches: large enough that a chunk outweighs the pool's hand-off (~1-2 us), small enough to
    // balance two to eight workers on a 100 000-vertex draw.
    constexpr uint32_t kChunk = 64 * shader::kLanes;
    const unsigned threads = std::min<unsigned>(pool.num_workers(), static_cast<unsigned>(workers.size()));
    if (threads <= 1 || n < 2 * kChunk || writes_memory(*cfg.program)) {
        shade_range(cfg, fetches, indices, 0, n, *workers[0], out);
        return;
    }
    for (unsigned w = 0; w < threads; ++w) cfg.program->reserve(workers[w]->scratch);
    pool.run((n + kChunk - 1) / kChunk, [&](unsigned w, size_t chunk) {
        geometry::ScopedFlushDenormals flush_denormals;  // fetch conversions as on the drawing thread
        const uint32_t first = static_cast<uint32_t>(chunk) * kChunk;
        shade_range(cfg, fetches, indices, first, std::min(n, first + kChunk), *workers[w], out);
    });
}

}  // namespace tilevk::rast::render
