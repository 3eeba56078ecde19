// Query commands at vkQueueSubmit: begin/end (occlusion, pipeline statistics), reset, timestamps, copies of results
// into a buffer.
// Occlusion counts come from rast/render: each draw recorded while a query is active carries a pointer to the
// query's value (DrawCall::samples_passed), to which the renderer adds the draw's passing samples once its tiles
// are rendered.
#include <cinttypes>

#include "buffer.h"
#include "execute.h"
#include "query_pool.h"
#include "vk_names.h"

namespace tilevk::icd {

uint64_t* active_occlusion_counter(const ExecState& st) {
    if (st.occlusion_pool == nullptr || st.occlusion_query >= st.occlusion_pool->count) return nullptr;
    return &st.occlusion_pool->slots[st.occlusion_query].value;
}

void publish_ended_queries(ExecState& st) {
    publish_statistics(st);
    for (auto [pool, query] : st.ended_in_pass) pool->make_available(query);
    st.ended_in_pass.clear();
}

void finish_queries(ExecState& st) {
    while (!st.statistics_queries.empty()) {
        QueryPool* pool = st.statistics_queries.back().pool;
        const uint32_t query = st.statistics_queries.back().query;
        log_error(
            "vkQueueSubmit: pipeline-statistics query %u was begun and never ended in its command buffer; "
            "ended now",
            query);
        end_statistics(st, *pool, query);
    }
    if (st.occlusion_pool != nullptr) {
        log_error("vkQueueSubmit: occlusion query %u was begun and never ended in its command buffer; ended now",
                  st.occlusion_query);
        st.ended_in_pass.emplace_back(st.occlusion_pool, st.occlusion_query);
        st.occlusion_pool = nullptr;
    }
    finish_rendering(st);  // renders anything left binned (invalid usage: a render pass left open) and publishes
}

namespace {
// In a multiview subpass a query uses as many consecutive queries as the subpass has views (vkCmdBeginQuery,
// "multiview"); each view runs the subpass's commands on its own (execute.cpp), so view k's results go to query + k,
// one of the distributions the spec allows.
uint32_t view_query(const ExecState& st, uint32_t query) {
    return st.render_pass != nullptr && st.view_mask != 0 ? query + st.view_ordinal : query;
}
}  // namespace

void exec_query(ExecState& st, const CmdBeginQuery& c) {
    const uint32_t query = view_query(st, c.query);
    if (c.pool->type == VK_QUERY_TYPE_PIPELINE_STATISTICS && query < c.pool->count) {
        end_statistics(st, *c.pool, query);  // begun twice (invalid usage): restarted
        begin_statistics(st, *c.pool, query);
        note_query_command_in_pass(st);  // lavapipe bins it into every tile (lp_setup_begin_query)
        return;
    }
    if (c.pool->type != VK_QUERY_TYPE_OCCLUSION && c.pool->type != VK_QUERY_TYPE_PIPELINE_STATISTICS) {
        log_error("vkCmdBeginQuery: a %s pool cannot be begun; ignored", vk_enum_name(c.pool->type));
        return;
    }
    if (query >= c.pool->count) {
        log_error("vkCmdBeginQuery: query %u is outside the pool of %u; ignored", query, c.pool->count);
        return;
    }
    c.pool->begin(query);
    note_query_command_in_pass(st);
    st.occlusion_pool = c.pool;
    st.occlusion_query = query;
}

void exec_query(ExecState& st, const CmdEndQuery& c) {
    const uint32_t query = view_query(st, c.query);
    if (c.pool->type == VK_QUERY_TYPE_PIPELINE_STATISTICS) {
        if (!end_statistics(st, *c.pool, query))
            log_error("vkCmdEndQuery: pipeline-statistics query %u is not active; ignored", query);
        note_query_command_in_pass(st);
        return;
    }
    if (c.pool != st.occlusion_pool || query != st.occlusion_query) {
        log_error("vkCmdEndQuery: query %u is not the active occlusion query; ignored", query);
        return;
    }
    st.occlusion_pool = nullptr;
    note_query_command_in_pass(st);
    if (st.render_pass != nullptr)
        st.ended_in_pass.emplace_back(c.pool, query);  // its draws may still be binned
    else
        c.pool->make_available(query);
}

void exec_query(ExecState& st, const CmdWriteTimestamp& c) {
    // Draws are binned until the renderer's pass ends; a timestamp after any stage but the top of the pipe must
    // follow their rendering, so it renders them first (lavapipe flushes its context the same way).
    if (c.stage != VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT) finish_rendering(st);
    const uint32_t query = view_query(st, c.query);
    if (c.pool->type != VK_QUERY_TYPE_TIMESTAMP || query >= c.pool->count) {
        log_error("vkCmdWriteTimestamp: query %u of a %s pool of %u queries cannot take a timestamp; ignored", query,
                  vk_enum_name(c.pool->type), c.pool->count);
        return;
    }
    note_query_command_in_pass(st);
    c.pool->write_timestamp(query, timestamp_now_ns());
}

void exec_query(ExecState&, const CmdCopyQueryPoolResults& c) {
    const Buffer* b = c.dst;
    if (b == nullptr || b->memory == nullptr || c.offset > b->size) {
        log_error("vkCmdCopyQueryPoolResults: destination buffer unbound or offset %" PRIu64 " out of range; skipped",
                  uint64_t(c.offset));
        return;
    }
    // Execution is in order, so every query ended earlier in the stream is available already: WAIT has nothing to
    // wait for, and a query still unavailable here could only be made available by a later submission.
    write_query_results(*c.pool, c.first, c.count, b->data() + c.offset, size_t(b->size - c.offset), c.stride, c.flags,
                        false);
}

void exec_query(ExecState&, const CmdResetQueryPool& c) {
    c.pool->reset(c.first, c.count);
}

}  // namespace tilevk::icd
