// The frame benchmark's scenes as plain data: pipelines (GLSL and fixed-function state), textures, vertices and
// the draws of one frame. frame_scenes.cpp builds them; frame_vk.cpp turns one into Vulkan objects on a device.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace tilevk::bench {

// One vertex of every scene: position (clip space), a colour or normal, a texture coordinate.
struct BenchVertex {
    float pos[4] = {0, 0, 0, 1};
    float color[4] = {1, 1, 1, 1};
    float uv[2] = {0, 0};
};

struct BenchPipeline {
    std::string vertex_glsl, fragment_glsl;
    bool blend = false;  // SRC_ALPHA, ONE_MINUS_SRC_ALPHA on colour and alpha
    bool depth_test = false, depth_write = false;
    VkCullModeFlags cull = VK_CULL_MODE_NONE;
    bool textured = false;  // binds set 0 = one combined image sampler (fragment stage)
};

struct BenchTexture {
    uint32_t size = 256;  // square, RGBA8, a full mip chain
    uint32_t seed = 1;    // pattern variant
    VkFilter filter = VK_FILTER_LINEAR;
    VkSamplerMipmapMode mip_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
};

struct BenchDraw {
    uint32_t pipeline = 0;
    int32_t texture = -1;       // index into BenchScene::textures (textured pipelines)
    uint32_t first_vertex = 0;  // into BenchScene::vertices
    uint32_t vertex_count = 0;
    float push[8] = {0, 0, 0, 0, 1, 1, 1, 1};  // vec4 offset, vec4 tint: the vertex shader's push constants
    VkRect2D scissor = {{0, 0}, {0, 0}};       // extent 0: the whole target
};

struct BenchScene {
    std::string name, description;
    uint32_t width = 1920, height = 1080;
    VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  // 4: rendered at 4x and resolved in the render pass
    VkFormat depth = VK_FORMAT_UNDEFINED;
    float clear_color[4] = {0.1f, 0.1f, 0.15f, 1.0f};
    std::vector<BenchPipeline> pipelines;
    std::vector<BenchTexture> textures;
    std::vector<BenchVertex> vertices;
    std::vector<BenchDraw> draws;
};

// The small-triangle scenes' triangle count (default 100000; smaller for smoke tests).
void set_small_triangle_count(uint32_t n);

// The names of every scene (each also as NAME@WxH for another target size).
std::vector<std::string> scene_names();
// Builds a scene by name ("tri16_flat", "blend16@1024x1024", ...); throws std::runtime_error for an unknown name.
BenchScene make_scene(const std::string& name);

}  // namespace tilevk::bench
