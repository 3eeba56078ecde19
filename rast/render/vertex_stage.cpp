// Vertex stage: attribute fetch -> vertex shader (SoA, 16 lanes) -> clip mask and viewport per vertex.
#include "rast/render/vertex_stage.h"

#include <algorithm>
#include <cstring>

#include "rast/geometry/viewport.h"

namespace tilevk::rast::render {
namespace {

float as_float(uint32_t bits) {
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

void fetch_batch(const VertexStageConfig& cfg, const uint32_t* idx, uint32_t count, shader::VertexBatch& batch) {
    const VertexInputState& in = *cfg.input;
    const uint32_t num_buffers = static_cast<uint32_t>(in.buffers.size());
    for (uint32_t lane = 0; lane < count; ++lane) {
        batch.vertex_index[lane] = idx[lane];
        batch.instance_index[lane] = cfg.first_instance + cfg.instance;
    }
    for (size_t a = 0; a < in.attribs.size(); ++a) {
        const geometry::VertexAttribDesc& desc = in.attribs[a];
        const uint32_t loc = in.locations[a];
        if (loc >= shader::kMaxLocations) continue;
        for (uint32_t lane = 0; lane < count; ++lane) {
            geometry::FetchedAttrib value{{0, 0, 0, 0}};
            if (desc.binding < num_buffers) {
                const geometry::VertexBufferView& vb = in.buffers[desc.binding];
                value = geometry::fetch_attribute(
                    desc, vb, geometry::element_index(vb, idx[lane], cfg.instance, cfg.first_instance));
            }
            for (int c = 0; c < 4; ++c) batch.inputs[loc][c][lane] = value.w[c];
        }
    }
}

}  // namespace

void shade_vertices(const VertexStageConfig& cfg, std::span<const uint32_t> indices, shader::Scratch& scratch,
                    ShadedVertices* out) {
    const geometry::VertexLayout layout = cfg.varyings->layout();
    const uint32_t stride = geometry::vertex_floats(layout);
    const uint32_t n = static_cast<uint32_t>(indices.size());
    out->floats_per_vertex = stride;
    out->records.resize(size_t(n) * stride);
    out->clipmask.resize(n);
    out->point_size.resize(n);
    const bool writes_point_size = cfg.program->interface().builtins_written & shader::bit(shader::BuiltIn::PointSize);

    shader::VertexBatch batch;
    batch.base_vertex = cfg.base_vertex;
    batch.base_instance = cfg.first_instance;
    for (uint32_t first = 0; first < n; first += shader::kLanes) {
        const uint32_t count = std::min<uint32_t>(shader::kLanes, n - first);
        batch.count = count;
        fetch_batch(cfg, indices.data() + first, count, batch);
        cfg.program->run_vertex(*cfg.bindings, batch, scratch);
        for (uint32_t lane = 0; lane < count; ++lane) {
            float* rec = out->records.data() + size_t(first + lane) * stride;
            for (int c = 0; c < 4; ++c) rec[geometry::kClipPosOffset + c] = as_float(batch.position[c][lane]);
            const uint32_t num_inputs = static_cast<uint32_t>(cfg.varyings->slot_location.size());
            for (uint32_t s = 0; s < num_inputs; ++s) {
                const uint32_t loc = cfg.varyings->slot_location[s];
                for (int c = 0; c < 4; ++c)
                    rec[geometry::kAttribOffset + 4 * s + c] = as_float(batch.outputs[loc][c][lane]);
            }
            out->clipmask[first + lane] = geometry::compute_clipmask(cfg.clip, rec + geometry::kClipPosOffset);
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

}  // namespace tilevk::rast::render
