// shader::ProgramCache: identical inputs share one program; any difference (words, stage, entry point,
// specialization) builds another; failures are never kept; the least recently used program goes first.
#include <gtest/gtest.h>

#include <bit>
#include <thread>
#include <vector>

#include "glsl.h"
#include "shader/program_cache.h"

namespace tilevk::shader {
namespace {

const char* kFs = R"(#version 450
layout(constant_id = 3) const float kScale = 1.0;
layout(location = 0) in vec4 c;
layout(location = 0) out vec4 o;
void main() { o = c * kScale; })";

SpecConstants scale(float v) {
    SpecConstant c;
    c.id = 3;
    c.words = {std::bit_cast<uint32_t>(v)};
    return {c};
}

TEST(ProgramCache, IdenticalInputsShareOneProgram) {
    const std::vector<uint32_t> spirv = test::compile_glsl(Stage::Fragment, kFs);
    ProgramCache cache;
    bool hit = true;
    const Result a = cache.get_or_create(spirv, Stage::Fragment, "main", {}, &hit);
    ASSERT_TRUE(a) << a.error;
    EXPECT_FALSE(hit);
    const std::vector<uint32_t> copy = spirv;  // equal words in another buffer
    const Result b = cache.get_or_create(copy, Stage::Fragment, "main", {}, &hit);
    EXPECT_TRUE(hit);
    EXPECT_EQ(a.program.get(), b.program.get());
    EXPECT_EQ(cache.size(), 1u);
}

TEST(ProgramCache, AnyDifferenceBuildsAnother) {
    const std::vector<uint32_t> spirv = test::compile_glsl(Stage::Fragment, kFs);
    ProgramCache cache;
    bool hit = true;
    const Result base = cache.get_or_create(spirv, Stage::Fragment, "main", scale(2.0f), &hit);
    ASSERT_TRUE(base) << base.error;
    const Result other_value = cache.get_or_create(spirv, Stage::Fragment, "main", scale(3.0f), &hit);
    EXPECT_FALSE(hit);
    ASSERT_TRUE(other_value);
    EXPECT_NE(base.program.get(), other_value.program.get());
    const Result no_spec = cache.get_or_create(spirv, Stage::Fragment, "main", {}, &hit);
    EXPECT_FALSE(hit);
    // A module differing in one word (the generator's magic word is not checked by anything but the key).
    std::vector<uint32_t> changed = spirv;
    changed[2] ^= 1u;
    const Result other_words = cache.get_or_create(changed, Stage::Fragment, "main", {}, &hit);
    EXPECT_FALSE(hit);
    // Another entry point name and another stage: refused by Program::create (no such entry point), not cached.
    const Result other_entry = cache.get_or_create(spirv, Stage::Fragment, "main2", {}, &hit);
    EXPECT_FALSE(hit);
    EXPECT_FALSE(other_entry);
    const Result other_stage = cache.get_or_create(spirv, Stage::Vertex, "main", {}, &hit);
    EXPECT_FALSE(hit);
    EXPECT_FALSE(other_stage);
    // And the first one is still there.
    const Result again = cache.get_or_create(spirv, Stage::Fragment, "main", scale(2.0f), &hit);
    EXPECT_TRUE(hit);
    EXPECT_EQ(again.program.get(), base.program.get());
}

TEST(ProgramCache, FailuresAreNotKept) {
    ProgramCache cache;
    const std::vector<uint32_t> garbage = {0x07230203u, 0x00010000u, 0u, 5u, 0u, 0xFFFFFFFFu};
    for (int i = 0; i < 2; ++i) {
        bool hit = true;
        const Result r = cache.get_or_create(garbage, Stage::Fragment, "main", {}, &hit);
        EXPECT_FALSE(hit);
        EXPECT_FALSE(r);
        EXPECT_FALSE(r.error.empty());
    }
    EXPECT_EQ(cache.size(), 0u);
}

TEST(ProgramCache, LeastRecentlyUsedGoesFirst) {
    const std::vector<uint32_t> spirv = test::compile_glsl(Stage::Fragment, kFs);
    ProgramCache cache(2);
    bool hit = false;
    cache.get_or_create(spirv, Stage::Fragment, "main", scale(1.0f), &hit);  // A
    cache.get_or_create(spirv, Stage::Fragment, "main", scale(2.0f), &hit);  // B
    cache.get_or_create(spirv, Stage::Fragment, "main", scale(1.0f), &hit);  // A used again
    EXPECT_TRUE(hit);
    cache.get_or_create(spirv, Stage::Fragment, "main", scale(3.0f), &hit);  // C evicts B
    EXPECT_EQ(cache.size(), 2u);
    cache.get_or_create(spirv, Stage::Fragment, "main", scale(1.0f), &hit);
    EXPECT_TRUE(hit);
    cache.get_or_create(spirv, Stage::Fragment, "main", scale(2.0f), &hit);
    EXPECT_FALSE(hit);
}

TEST(ProgramCache, ConcurrentRequestsGetOneKeptProgram) {
    const std::vector<uint32_t> spirv = test::compile_glsl(Stage::Fragment, kFs);
    ProgramCache cache;
    std::vector<std::shared_ptr<const Program>> got(4);
    std::vector<std::thread> threads;
    for (size_t i = 0; i < got.size(); ++i)
        threads.emplace_back([&, i] { got[i] = cache.get_or_create(spirv, Stage::Fragment, "main", {}).program; });
    for (std::thread& t : threads) t.join();
    for (const auto& p : got) EXPECT_NE(p, nullptr);
    EXPECT_EQ(cache.size(), 1u);
    bool hit = false;
    const Result later = cache.get_or_create(spirv, Stage::Fragment, "main", {}, &hit);
    EXPECT_TRUE(hit);
}

}  // namespace
}  // namespace tilevk::shader
