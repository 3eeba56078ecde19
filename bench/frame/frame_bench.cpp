// tilevk-frame-bench: whole frames of one scene on one Vulkan driver, as an application renders them.
//
//   tilevk-frame-bench --device tilevk --scene tri16_flat [--frames 7] [--warmup 2]
//   tilevk-frame-bench --list
//
// Prints one JSON object: the cold pipeline creation and first frame, every timed frame (record + submit + wait;
// its wall time and the process's CPU time, all threads),
// the process's peak RSS and its RSS once the device exists, minor page faults per timed frame, and a hash of the
// final image. One process runs one driver, so the RSS is that driver's; run_frame_bench.py alternates the
// processes of both drivers and compares them (bench/frame/README.md). VK_ICD_FILENAMES defaults to the driver's
// own manifest only.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>
#include <vector>

#include "alloc_count.h"
#include "compute_vk.h"
#include "frame_scene.h"
#include "frame_vk.h"
#include "vk_context.hpp"

namespace {

// CPU time of the whole process (every thread), milliseconds.
double process_cpu_ms() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return (ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) * 1e3 + (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) / 1e3;
}

long rss_kb() {
    std::ifstream f("/proc/self/statm");
    long pages = 0, resident = 0;
    f >> pages >> resident;
    return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

// Parses "3,10-20,99" into draw indices; false for anything else.
bool parse_draw_list(const std::string& text, std::vector<bool>& keep, size_t draws) {
    keep.assign(draws, false);
    size_t pos = 0;
    while (pos < text.size()) {
        size_t end = text.find(',', pos);
        if (end == std::string::npos) end = text.size();
        const std::string item = text.substr(pos, end - pos);
        unsigned long first = 0, last = 0;
        char dash = 0;
        const int n = std::sscanf(item.c_str(), "%lu%c%lu", &first, &dash, &last);
        if (n == 1)
            last = first;
        else if (n != 3 || dash != '-')
            return false;
        if (first > last || last >= draws) return false;
        for (unsigned long i = first; i <= last; ++i) keep[i] = true;
        pos = end + 1;
    }
    return true;
}

// What one process measured: cold pipeline, first frame, the timed frames, faults and allocations while timing,
// and the hash of the final result.
struct Timed {
    double cold_ms = 0, first_ms = 0;
    std::vector<double> times, record, cpu;
    long faults = 0;
    uint64_t allocs = 0, hash = 0;
};

// The same timing for a graphics scene (SceneOnDevice) and a compute kernel (ComputeOnDevice).
template <typename On>
Timed time_frames(On& on, int frames, int warmup) {
    Timed t;
    t.cold_ms = on.cold_pipeline_ms();
    t.first_ms = on.frame();
    for (int i = 0; i < warmup; ++i) on.frame();
    t.times.reserve(size_t(frames));  // the harness itself allocates nothing while it counts
    t.record.reserve(size_t(frames));
    t.cpu.reserve(size_t(frames));
    rusage before{}, after{};
    getrusage(RUSAGE_SELF, &before);
    const uint64_t allocs_before = tilevk::bench::allocations();
    for (int i = 0; i < frames; ++i) {
        const double cpu0 = process_cpu_ms();
        t.times.push_back(on.frame());
        t.cpu.push_back(process_cpu_ms() - cpu0);
        t.record.push_back(on.last_record_ms());
    }
    t.allocs = tilevk::bench::allocations() - allocs_before;
    getrusage(RUSAGE_SELF, &after);
    t.faults = after.ru_minflt - before.ru_minflt;
    t.hash = on.image_hash();
    return t;
}

// Binary PPM of the final image (alpha dropped), for looking at it.
void write_ppm(const std::string& path, const tilevk::bench::BenchScene& scene, const uint8_t* px) {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) return;
    std::fprintf(f, "P6\n%u %u\n255\n", scene.width, scene.height);
    for (size_t i = 0; i < size_t(scene.width) * scene.height; ++i) std::fwrite(px + 4 * i, 1, 3, f);
    std::fclose(f);
}

int usage() {
    std::fprintf(stderr,
                 "usage: tilevk-frame-bench --device tilevk|llvmpipe --scene NAME[@WxH] [--frames N] [--warmup N] "
                 "[--triangles N] [--dump FILE.ppm] [--draws LIST]\n"
                 "       --draws 0-99,245: render only those draws of the scene (indices into its draw list), to\n"
                 "       narrow down which draw makes two drivers' images differ\n"
                 "       tilevk-frame-bench --list\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    std::string device, scene_name, dump, draw_list;
    int frames = 7, warmup = 2;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
        if (a == "--list") {
            for (const std::string& n : tilevk::bench::scene_names()) std::printf("%s\n", n.c_str());
            for (const std::string& n : tilevk::bench::compute_scene_names()) std::printf("%s\n", n.c_str());
            return 0;
        }
        if (a == "--device") {
            device = value();
        } else if (a == "--scene") {
            scene_name = value();
        } else if (a == "--frames") {
            frames = std::atoi(value().c_str());
        } else if (a == "--triangles") {
            tilevk::bench::set_small_triangle_count(uint32_t(std::atoi(value().c_str())));
        } else if (a == "--dump") {
            dump = value();
        } else if (a == "--draws") {
            draw_list = value();
        } else if (a == "--warmup") {
            warmup = std::atoi(value().c_str());
        } else {
            return usage();
        }
    }
    if (device.empty() || scene_name.empty() || frames < 1 || warmup < 0) return usage();
    if (!std::getenv("VK_ICD_FILENAMES")) {
        const std::string icd = device == "tilevk" ? TILEVK_BUILD_ROOT "/tilevk_icd.json" : TILEVK_LVP_ICD;
        setenv("VK_ICD_FILENAMES", icd.c_str(), 1);
    }
    try {
        // A compute scene is one kernel (compute_vk.h); its BenchScene carries only the name, description and size.
        const bool compute = tilevk::bench::is_compute_scene(scene_name);
        tilevk::bench::BenchScene scene;
        if (compute) {
            scene.name = scene_name;
            scene.description = tilevk::bench::compute_scene_description(scene_name);
            tilevk::bench::compute_scene_size(scene_name, scene.width, scene.height);
        } else {
            scene = tilevk::bench::make_scene(scene_name);
        }
        if (!draw_list.empty() && !compute) {
            std::vector<bool> keep;
            if (!parse_draw_list(draw_list, keep, scene.draws.size())) {
                std::fprintf(stderr, "tilevk-frame-bench: bad --draws '%s' (the scene has %zu draws)\n",
                             draw_list.c_str(), scene.draws.size());
                return 2;
            }
            std::vector<tilevk::bench::BenchDraw> kept;
            for (size_t i = 0; i < keep.size(); ++i)
                if (keep[i]) kept.push_back(scene.draws[i]);
            scene.draws = std::move(kept);
        }
        tilevk::cts::Instance instance;
        tilevk::cts::DeviceContext ctx;
        std::string reason;
        if (!instance.open(device, false, ctx, reason)) {
            std::fprintf(stderr, "tilevk-frame-bench: %s\n", reason.c_str());
            return 1;
        }
        const long base_rss = rss_kb();
        Timed t;
        if (compute) {
            tilevk::bench::ComputeOnDevice on(ctx, scene_name);
            t = time_frames(on, frames, warmup);
        } else {
            tilevk::bench::SceneOnDevice on(ctx, scene);
            t = time_frames(on, frames, warmup);
            if (!dump.empty()) write_ppm(dump, scene, on.image_bytes());
        }
        const double cold_ms = t.cold_ms, first_ms = t.first_ms;
        const std::vector<double>&times = t.times, &record = t.record, &cpu = t.cpu;
        const long faults = t.faults;
        const uint64_t allocs = t.allocs, hash = t.hash;
        rusage ru{};
        getrusage(RUSAGE_SELF, &ru);
        size_t tris = 0;
        for (const auto& d : scene.draws) tris += d.vertex_count / 3;
        std::printf(
            "{\"scene\": \"%s\", \"device\": \"%s\", \"device_name\": \"%s\", \"width\": %u, \"height\": %u, "
            "\"samples\": %d, \"draws\": %zu, \"triangles\": %zu, \"cold_pipeline_ms\": %.3f, "
            "\"first_frame_ms\": %.3f, \"frames_ms\": [",
            scene.name.c_str(), device.c_str(), ctx.name.c_str(), scene.width, scene.height, int(scene.samples),
            scene.draws.size(), tris, cold_ms, first_ms);
        for (size_t i = 0; i < times.size(); ++i) std::printf("%s%.3f", i ? ", " : "", times[i]);
        std::printf("], \"record_ms\": [");
        for (size_t i = 0; i < record.size(); ++i) std::printf("%s%.3f", i ? ", " : "", record[i]);
        std::printf("], \"cpu_ms\": [");
        for (size_t i = 0; i < cpu.size(); ++i) std::printf("%s%.3f", i ? ", " : "", cpu[i]);
        std::printf(
            "], \"peak_rss_kb\": %ld, \"base_rss_kb\": %ld, \"minor_faults_per_frame\": %.1f, "
            "\"allocations_per_frame\": %s, \"image_hash\": \"%016llx\", \"description\": \"%s\"}\n",
            ru.ru_maxrss, base_rss, double(faults) / frames,
            tilevk::bench::allocations_counted() ? std::to_string(double(allocs) / frames).c_str() : "null",
            static_cast<unsigned long long>(hash), scene.description.c_str());
        tilevk::cts::Instance::close(ctx);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tilevk-frame-bench: %s: %s\n", scene_name.c_str(), e.what());
        return 1;
    }
    return 0;
}
