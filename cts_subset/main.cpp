// tilevk-cts: runs the conformance subset on two Vulkan devices in one process and compares their images.
#include <fnmatch.h>
#include <sys/stat.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <thread>

#include "case.hpp"
#include "expectations.hpp"
#include "fuzz.hpp"
#include "glsl.hpp"
#include "oracle.hpp"
#include "png_writer.hpp"
#include "render.hpp"
#include "results.hpp"
#include "validation.hpp"

using namespace tilevk::cts;

namespace {

struct Options {
    bool list = false;
    std::string filter = "*", device = "tilevk", ref = "llvmpipe", log, junit, json, png_dir, start_after;
    bool device_is_prefix = true, png_all = false, selftest_perturb = false;
    bool validation = false;
    bool strict = false;  // NotSupported on the device under test only is a failure (and missing test data)
    bool selftest_validation = false;  // hidden: records one invalid barrier, which --validation must report
    int timing = 0;
    int case_timeout = 300;  // seconds; a hung driver ends the process (run_one.sh resumes after the case)
    std::string expectations = TILEVK_CTS_EXPECTATIONS;  // the known differences (expectations.txt)
    FuzzConfig fuzz;                                     // --fuzz: fuzz.hpp
    bool fuzzing = false;
};

void usage() {
    std::puts(
        "usage: tilevk-cts [--list] [--filter GLOB] [--device NAME] [--ref NAME] [--log FILE] [--junit FILE]\n"
        "                  [--json FILE] [--png-dir DIR] [--timing N] [--start-after CASE] [--png-all]\n"
        "                  [--case-timeout SECONDS (default 300)] [--spirv 1.0|1.3|1.5]\n"
        "                  [--selftest-perturb] [--validation] [--strict] [--expectations FILE]\n"
        "                  [--fuzz MINUTES [--fuzz-seed FIRST] [--fuzz-seeds COUNT] [--fuzz-log FILE]]\n"
        "  --device/--ref pick devices by name substring (default: the device whose name starts with 'tilevk',\n"
        "  against 'llvmpipe'). Both may be the same device: two VkDevices are created on it.\n"
        "  --selftest-perturb flips one bit of the device-under-test's read-back (proves the comparison).\n"
        "  --validation enables VK_LAYER_KHRONOS_validation: any warning or error fails the case it arrives in.\n"
        "  --strict fails a case that is NotSupported on the device under test but not on the reference, or\n"
        "  whose test data is missing (nothing is skipped silently; CI runs the subset this way).\n"
        "  --png-dir writes ours/ref/diff PNGs of failing cases (of every case with --png-all).\n"
        "  --spirv compiles every shader to that SPIR-V version (default 1.0) and asks for Vulkan 1.0, 1.1 or 1.2.\n"
        "  --expectations FILE: the known differences (default: the source tree's cts_subset/expectations.txt).\n"
        "  --fuzz runs random, extreme-vertex and SPIR-V-mutation seeds from FIRST (default: today's, printed)\n"
        "  for MINUTES or COUNT seeds; failures are minimised and printed with their reproduction (fuzz.hpp).\n"
        "  VK_ICD_FILENAMES defaults to this build's tilevk_icd.json and lavapipe's manifest.");
}

bool parse(int argc, char** argv, Options& o) {
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&](std::string& dst) {
            if (i + 1 >= argc) return false;
            dst = argv[++i];
            return true;
        };
        std::string n;
        if (a == "--list")
            o.list = true;
        else if (a == "--filter") {
            if (!value(o.filter)) return false;
        } else if (a == "--device") {
            if (!value(o.device)) return false;
            o.device_is_prefix = false;
        } else if (a == "--ref") {
            if (!value(o.ref)) return false;
        } else if (a == "--log") {
            if (!value(o.log)) return false;
        } else if (a == "--junit") {
            if (!value(o.junit)) return false;
        } else if (a == "--json") {
            if (!value(o.json)) return false;
        } else if (a == "--png-dir") {
            if (!value(o.png_dir)) return false;
        } else if (a == "--png-all")
            o.png_all = true;
        else if (a == "--selftest-perturb")
            o.selftest_perturb = true;
        else if (a == "--strict")
            o.strict = true;
        else if (a == "--validation")
            o.validation = true;
        else if (a == "--selftest-validation")
            o.selftest_validation = true;
        else if (a == "--expectations") {
            if (!value(o.expectations)) return false;
        } else if (a == "--spirv") {
            if (!value(n)) return false;
            if (n == "1.0")
                set_spirv_target(SpirvTarget::kSpirv10);
            else if (n == "1.3")
                set_spirv_target(SpirvTarget::kSpirv13);
            else if (n == "1.5")
                set_spirv_target(SpirvTarget::kSpirv15);
            else if (n == "1.6")
                set_spirv_target(SpirvTarget::kSpirv16);
            else
                return false;
        } else if (a == "--start-after") {
            if (!value(o.start_after)) return false;
        } else if (a == "--case-timeout") {
            if (!value(n)) return false;
            char* end = nullptr;
            long v = std::strtol(n.c_str(), &end, 10);
            if (*end || v < 1 || v > 86400) return false;
            o.case_timeout = int(v);
        } else if (a == "--fuzz" || a == "--fuzz-seed" || a == "--fuzz-seeds") {
            if (!value(n)) return false;
            char* end = nullptr;
            const double v = std::strtod(n.c_str(), &end);
            if (*end || !(v >= 0) || v > 4e9) return false;
            if (a == "--fuzz")
                o.fuzz.minutes = v, o.fuzzing = true;
            else if (a == "--fuzz-seed")
                o.fuzz.first_seed = uint32_t(v);
            else
                o.fuzz.max_seeds = uint32_t(v);
        } else if (a == "--fuzz-log") {
            if (!value(o.fuzz.log)) return false;
        } else if (a == "--timing") {
            if (!value(n)) return false;
            char* end = nullptr;
            long v = std::strtol(n.c_str(), &end, 10);
            if (*end || v < 0 || v > 10000) return false;
            o.timing = int(v);
        } else
            return false;
    }
    return true;
}

bool file_exists(const std::string& p) {
    struct stat st;
    return stat(p.c_str(), &st) == 0;
}

// The loader finds both drivers through VK_ICD_FILENAMES; default to this build's manifest plus lavapipe's.
std::string set_icd_filenames() {
    if (const char* env = std::getenv("VK_ICD_FILENAMES"); env && *env) return env;
    std::string list;
    for (const std::string& p : {std::string(TILEVK_BUILD_ROOT) + "/tilevk_icd.json", std::string(TILEVK_LVP_ICD)})
        if (file_exists(p)) list += (list.empty() ? "" : ":") + p;
    if (!list.empty()) setenv("VK_ICD_FILENAMES", list.c_str(), 1);
    return list;
}

double median(std::vector<double> v) {
    if (v.empty()) return -1;
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string file_safe(std::string s) {
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
    return s;
}

void save_pngs(const std::string& dir, const std::string& name, const std::vector<Plane>& ours,
               const std::vector<Plane>& ref) {
    mkdir(dir.c_str(), 0755);
    for (size_t i = 0; i < ours.size() && i < ref.size(); ++i) {
        std::string base = dir + "/" + file_safe(name) + "." + ours[i].name;
        write_png(base + ".ours.png", ours[i].width, ours[i].height, to_rgba8(ours[i]));
        write_png(base + ".ref.png", ref[i].width, ref[i].height, to_rgba8(ref[i]));
        write_png(base + ".diff.png", ours[i].width, ours[i].height, diff_rgba8(ours[i], ref[i]));
    }
}

// Who the validation layer's messages belong to while a case runs: the side being recorded or judged.
struct Sides {
    ValidationLog* log = nullptr;  // null without --validation
    std::string ours, ref;         // labels of the two devices in messages
    void enter(const std::string& scope, const std::string& side) const {
        if (log) log->set_scope(scope, side);
    }
};

// "validation: N messages (tilevk 2, llvmpipe 1); first: [tilevk] error VUID-...: text"; empty without messages.
// Every message also goes to stderr, with its case.
std::string validation_verdict(const std::string& scope, const std::vector<ValidationMessage>& msgs) {
    if (msgs.empty()) return {};
    std::map<std::string, int> per_device;
    for (const ValidationMessage& m : msgs) {
        ++per_device[m.device];
        std::fprintf(stderr, "validation: %s: %s\n", scope.c_str(), format_message(m).c_str());
    }
    std::string counts;
    for (const auto& [device, n] : per_device)
        counts += (counts.empty() ? "" : ", ") + device + " " + std::to_string(n);
    return "validation: " + std::to_string(msgs.size()) + " message" + (msgs.size() == 1 ? "" : "s") + " (" + counts +
           "); first: " + format_message(msgs.front());
}

// The two frames' planes compared (reference defects and named differences applied), the case's independent check
// and the coverage oracle run on both; fills r's counts, notes and verdicts and returns why the case fails, if it
// does.
std::string judge_frames(const Case& c, const DeviceContext& ours, const DeviceContext& ref, const Options& o,
                         const Scene& scene, const RenderResult& a, const RenderResult& b, CaseResult& r) {
    std::string why;
    if (a.planes.size() != b.planes.size()) why = "different number of read-back planes";
    // A per-frame named difference: the reference fails the independent check that the device under test passes.
    std::string ca, cb;
    if (c.check) ca = c.check(a.planes), cb = c.check(b.planes);
    const bool reference_wrong =
        c.check && !c.named_difference.empty() && !o.selftest_perturb && ca.empty() && !cb.empty();
    for (size_t i = 0; i < a.planes.size() && i < b.planes.size(); ++i) {
        PlaneDiff d = compare_planes(a.planes[i], b.planes[i]);
        if (!c.reference_defect.plane.empty() && d.plane == c.reference_defect.plane) {
            if (!d.problem.empty() && why.empty()) why = d.problem;  // shape mismatches still fail
            r.note += (r.note.empty() ? "" : "; ") + std::string("reference defect in '") + d.plane + "' (" +
                      c.reference_defect.reason + "): " + std::to_string(d.differing) + " of " +
                      std::to_string(d.total) + " values differ, not compared";
            continue;
        }
        if (!d.problem.empty() && why.empty()) why = d.problem;
        r.differing += d.differing;
        r.total += d.total;
        r.max_error = std::max(r.max_error, d.max_error);
        if (d.differing && reference_wrong) {
            r.note += (r.note.empty() ? "" : "; ") + std::string("named difference (") + c.named_difference +
                      "): " + d.plane + " " + std::to_string(d.differing) +
                      " pixels differ; the reference fails the check: " + cb;
            continue;
        }
        if (d.differing && why.empty()) {
            char buf[160];
            std::snprintf(buf, sizeof buf, "%s: %llu of %llu pixels differ from the reference, max error %g",
                          d.plane.c_str(), static_cast<unsigned long long>(d.differing),
                          static_cast<unsigned long long>(d.total), d.max_error);
            why = buf + std::string("; first ") + d.first;
        }
    }
    // The harness's own proof (--device llvmpipe --ref llvmpipe): a case whose named difference says the reference
    // is wrong expects the reference driver to fail its check, on both sides alike.
    const bool reference_defect_on_both =
        !c.named_difference.empty() && ours.name == ref.name && !ca.empty() && ca == cb;
    if (reference_defect_on_both)
        r.note += (r.note.empty() ? "" : "; ") + std::string("named difference (") + c.named_difference +
                  "): the reference driver fails the check on both sides: " + ca;
    if (c.check && !reference_defect_on_both) {
        r.check = ca.empty() && cb.empty() ? "ok" : !ca.empty() ? ca : "reference: " + cb;
        if (why.empty() && !ca.empty()) why = "independent check: " + ca;
        if (why.empty() && !cb.empty() && !reference_wrong) why = "independent check failed on the reference: " + cb;
    }
    if (const CoverageOracle& oracle = coverage_oracle()) {
        // Judged on both devices: the reference must agree with rast's reference coverage too.
        const OracleVerdict va = oracle(scene, a.planes), vb = oracle(scene, b.planes);
        if (!va.applies) {
            r.oracle = "n/a: " + va.note;
        } else {
            r.oracle = va.error.empty() && vb.error.empty() ? "ok (" + va.note + ")"
                       : !va.error.empty()                  ? va.error
                                                            : "reference: " + vb.error;
            if (why.empty() && !va.error.empty()) why = "coverage oracle: " + va.error;
            if (why.empty() && !vb.error.empty()) why = "coverage oracle failed on the reference: " + vb.error;
        }
    }
    return why;
}

CaseResult run_case_body(const Case& c, const DeviceContext* ours, const std::string& ours_missing,
                         const DeviceContext& ref, const Options& o, const Sides& sides, bool bad) {
    CaseResult r;
    r.name = c.name;
    r.note = c.note;
    r.check = c.check ? "pending" : "none";
    auto fail = [&](std::string why) {
        r.status = Status::kFail;
        r.reason = std::move(why);
        return r;
    };
    Scene scene;
    try {
        scene = c.scene();
    } catch (const std::exception& e) {
        if (o.strict) return fail(std::string("test data unavailable (--strict): ") + e.what());
        r.status = Status::kNotSupported;
        r.reason = std::string("test data unavailable: ") + e.what();
        return r;
    }
    // Shaders are compiled here first, so a GLSL mistake is blamed on the harness, not on either driver.
    try {
        for (const Draw& d : scene.draws) {
            compile_glsl(Stage::kVertex, vertex_source(d));
            compile_glsl(Stage::kFragment, fragment_source(d, scene.target.color != VK_FORMAT_UNDEFINED));
        }
    } catch (const std::exception& e) {
        return fail(std::string("harness: ") + e.what());
    }
    if (!ours) {
        // Still time the reference, so the report shows lavapipe's side while tilevk is missing.
        sides.enter(c.name, sides.ref);
        if (unsupported(ref, scene).empty()) {
            try {
                RenderResult b = render(ref, scene, o.timing, bad);
                r.ref_ms = median(b.frame_ms);
                r.ref_pipeline_ms = b.pipeline_ms;
            } catch (const std::exception&) {
            }
        }
        return fail(ours_missing);
    }
    sides.enter(c.name, sides.ours);
    if (auto why = unsupported(*ours, scene); !why.empty()) {
        if (o.strict && unsupported(ref, scene).empty())
            return fail("--strict: not supported on " + ours->name + " but supported by " + ref.name + ": " + why);
        r.status = Status::kNotSupported;
        r.reason = ours->name + ": " + why;
        return r;
    }
    sides.enter(c.name, sides.ref);
    if (auto why = unsupported(ref, scene); !why.empty()) {
        r.status = Status::kNotSupported;
        r.reason = ref.name + ": " + why;
        return r;
    }
    // Both frames are built and run once for the images; then timed alternately (ours, ref, ours, ...) so that
    // load from elsewhere on the machine falls on both sides alike.
    RenderResult a, b;
    std::unique_ptr<Frame> fa, fb;
    sides.enter(c.name, sides.ours);
    try {
        fa = std::make_unique<Frame>(*ours, scene, bad);
        fa->submit();
        a.planes = fa->planes();
        a.pipeline_ms = fa->pipeline_ms();
    } catch (const std::exception& e) {
        return fail(ours->name + ": " + e.what());
    }
    sides.enter(c.name, sides.ref);
    try {
        fb = std::make_unique<Frame>(ref, scene, bad);
        fb->submit();
        b.planes = fb->planes();
        b.pipeline_ms = fb->pipeline_ms();
    } catch (const std::exception& e) {
        return fail("reference " + ref.name + ": " + e.what());
    }
    for (int i = 0; i < o.timing; ++i) {
        sides.enter(c.name, sides.ours);
        try {
            a.frame_ms.push_back(fa->submit());
        } catch (const std::exception& e) {
            return fail(ours->name + " (timing run " + std::to_string(i + 1) + "): " + e.what());
        }
        sides.enter(c.name, sides.ref);
        try {
            b.frame_ms.push_back(fb->submit());
        } catch (const std::exception& e) {
            return fail("reference " + ref.name + " (timing run " + std::to_string(i + 1) + "): " + e.what());
        }
    }
    // Each frame is destroyed under its own side's name (the layer checks object lifetimes there).
    sides.enter(c.name, sides.ours);
    fa.reset();
    sides.enter(c.name, sides.ref);
    fb.reset();
    sides.enter(c.name, "");
    // Harness self-test: one changed bit in our first plane must be caught by every comparison path.
    if (o.selftest_perturb && !a.planes.empty() && !a.planes[0].data.empty()) a.planes[0].data[0] ^= 1;
    r.ours_ms = median(a.frame_ms);
    r.ref_ms = median(b.frame_ms);
    r.ours_pipeline_ms = a.pipeline_ms;
    r.ref_pipeline_ms = b.pipeline_ms;
    const std::string why = judge_frames(c, *ours, ref, o, scene, a, b, r);
    if (!o.png_dir.empty() && (!why.empty() || o.png_all)) save_pngs(o.png_dir, c.name, a.planes, b.planes);
    if (!why.empty()) return fail(why);
    return r;
}

CaseResult run_case(const Case& c, const DeviceContext* ours, const std::string& ours_missing, const DeviceContext& ref,
                    const Options& o, const Sides& sides) {
    const bool bad = o.selftest_validation;
    // Any validation message fails the case ahead of every other verdict: an invalid command stream makes the
    // images meaningless.
    auto judged = [&](CaseResult r) {
        sides.enter("(between cases)", "");
        if (!sides.log) return r;
        std::vector<ValidationMessage> msgs = sides.log->take();
        for (const ValidationMessage& m : msgs) r.validation.push_back(format_message(m));
        if (std::string v = validation_verdict(c.name, msgs); !v.empty()) {
            if (r.status == Status::kFail) v += "; then: " + r.reason;
            r.status = Status::kFail;
            r.reason = v;
        }
        return r;
    };
    CaseResult r = run_case_body(c, ours, ours_missing, ref, o, sides, bad);
    return judged(std::move(r));
}

// A failure expectations.txt lists is an ExpectedFail; a listed case that passes fails (the list must stay true).
void apply_expected_fail(const Expectation& e, CaseResult& r) {
    if (r.status == Status::kFail) {
        r.status = Status::kExpectedFail;
        r.reason = "known difference (" + e.reason + "): " + r.reason;
    } else if (r.status == Status::kPass) {
        r.status = Status::kFail;
        r.reason = "unexpected pass: expectations.txt lists it as Fail (" + e.reason + ")";
    }
}

// Loads the known differences and hands the reference defects to their cases; false (with a message) on a
// malformed file.
bool apply_expectations(const std::string& path, CaseList& cases, std::map<std::string, Expectation>& fails) {
    std::map<std::string, Expectation> all;
    std::string error;
    if (!load_expectations(path, &all, &error)) {
        std::fprintf(stderr, "tilevk-cts: %s\n", error.c_str());
        return false;
    }
    for (Case& c : cases) {
        const auto it = all.find(c.name);
        if (it == all.end()) continue;
        if (it->second.kind == Expectation::kReferenceDefect)
            c.reference_defect = {it->second.plane, it->second.reason};
        else
            fails.emplace(c.name, it->second);
    }
    return true;
}

}  // namespace

// The cases --filter and --start-after select, in the list's order.
CaseList select_cases(const Options& o) {
    CaseList cases;
    for (Case& c : all_cases())
        if (fnmatch(o.filter.c_str(), c.name.c_str(), 0) == 0) cases.push_back(std::move(c));
    if (!o.start_after.empty()) {
        auto it = std::find_if(cases.begin(), cases.end(), [&](const Case& c) { return c.name == o.start_after; });
        if (it != cases.end()) cases.erase(cases.begin(), it + 1);
    }
    return cases;
}

// What the reports say about the run: devices asked for, ICD manifests, rasterizer method, thread counts.
RunInfo run_info(const Options& o) {
    RunInfo info;
    info.device = o.device;
    info.ref = o.ref;
    info.timing_reps = o.timing;
    info.icd_filenames = set_icd_filenames();
    if (const char* m = std::getenv("TILEVK_RAST")) info.rast_method = m;
    auto env = [](const char* k) {
        const char* v = std::getenv(k);
        return std::string(v ? v : "unset");
    };
    info.threads = "LP_NUM_THREADS=" + env("LP_NUM_THREADS") + " TILEVK_THREADS=" + env("TILEVK_THREADS");
    return info;
}

int main(int argc, char** argv) {
    set_coverage_oracle(rast_reference_oracle);
    Options o;
    if (!parse(argc, argv, o)) {
        usage();
        return 2;
    }
    CaseList cases = select_cases(o);
    std::map<std::string, Expectation> expected_fails;
    if (!apply_expectations(o.expectations, cases, expected_fails)) return 2;
    if (o.list) {
        for (const Case& c : cases)
            std::printf("%s%s\n", c.name.c_str(), c.note.empty() ? "" : ("  [" + c.note + "]").c_str());
        return 0;
    }

    RunInfo info = run_info(o);

    ValidationLog validation;  // outlives the instance: vkDestroyInstance may still report
    std::unique_ptr<Instance> instance;
    try {
        instance = std::make_unique<Instance>(o.validation ? &validation : nullptr);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "tilevk-cts: %s\n", e.what());
        return 3;
    }
    DeviceContext ref, ours;
    std::string why;
    if (!instance->open(o.ref, false, ref, why)) {
        std::fprintf(stderr, "tilevk-cts: reference device unavailable: %s\n", why.c_str());
        return 3;
    }
    std::string ours_missing;
    bool have_ours = instance->open(o.device, o.device_is_prefix, ours, ours_missing);
    info.device_found = have_ours;
    info.device_name = have_ours ? ours.name : "(absent) " + o.device;
    info.ref_name = ref.name;
    std::printf("tilevk-cts: %zu cases, device '%s' vs reference '%s'\n", cases.size(), info.device_name.c_str(),
                ref.name.c_str());
    if (!have_ours) std::printf("tilevk-cts: device under test unavailable: %s\n", ours_missing.c_str());
    Sides sides;
    if (o.validation) {
        // Labels name the driver; the same physical device on both sides gets the role added.
        sides.log = &validation;
        auto short_name = [](const std::string& n) { return n.substr(0, n.find(' ')); };  // "tilevk", "llvmpipe"
        sides.ours = short_name(info.device_name);
        sides.ref = short_name(ref.name) == sides.ours ? sides.ours + " (reference)" : short_name(ref.name);
        validation.add_device(uint64_t(ref.device), uint64_t(ref.queue), sides.ref);
        if (have_ours) validation.add_device(uint64_t(ours.device), uint64_t(ours.queue), sides.ours);
        std::printf("tilevk-cts: VK_LAYER_KHRONOS_validation on: any warning or error fails its case\n");
    }
    // Messages from instance and device creation belong to no case; they fail the run at the end.
    std::vector<ValidationMessage> outside = validation.take();

    if (o.fuzzing && !have_ours) {  // fuzzing compares the device under test with the reference: nothing to do
        Instance::close(ref);
        return 1;
    }

    // Watchdog: a driver that hangs inside a case must not hang the whole run. The JSON written before the case
    // names it as running, so run_one.sh records it as failed and resumes after it.
    std::atomic<int64_t> case_started{0};
    std::atomic<bool> done{false};
    std::thread watchdog([&] {
        while (!done) {
            std::this_thread::sleep_for(std::chrono::milliseconds(200));
            int64_t t = case_started.load();
            int64_t now =
                std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now().time_since_epoch())
                    .count();
            if (t && now - t > o.case_timeout) {
                std::fprintf(stderr, "tilevk-cts: case timed out after %d s; exiting\n", o.case_timeout);
                std::fflush(stdout);
                std::_Exit(124);
            }
        }
    });
    if (o.fuzzing) {
        const int failures = run_fuzz(
            o.fuzz, [&](const Case& c) { return run_case(c, &ours, ours_missing, ref, o, sides); },
            [&](DeviceContext& d) {
                std::string why;
                return instance->open(o.device, o.device_is_prefix, d, why);
            },
            [](DeviceContext& d) { Instance::close(d); });
        done = true;
        watchdog.join();
        Instance::close(ours);
        Instance::close(ref);
        instance.reset();
        return failures ? 1 : 0;
    }
    std::vector<CaseResult> results;
    int fails = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        if (!o.json.empty()) write_json(o.json, info, results, cases[i].name);  // survives a driver crash
        auto t0 = std::chrono::steady_clock::now();
        case_started = std::chrono::duration_cast<std::chrono::seconds>(t0.time_since_epoch()).count();
        CaseResult r = run_case(cases[i], have_ours ? &ours : nullptr, ours_missing, ref, o, sides);
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (auto it = expected_fails.find(r.name); it != expected_fails.end()) apply_expected_fail(it->second, r);
        fails += r.status == Status::kFail;
        std::printf("[%3zu/%zu] %-58s %s%s%s\n", i + 1, cases.size(), r.name.c_str(), status_name(r.status),
                    r.reason.empty() ? "" : ": ", r.reason.substr(0, 160).c_str());
        std::fflush(stdout);
        results.push_back(std::move(r));
    }
    done = true;
    watchdog.join();
    // Devices and instance go before the results are written: their destruction is validated too.
    sides.enter("(teardown)", sides.ours);
    Instance::close(ours);
    sides.enter("(teardown)", sides.ref);
    Instance::close(ref);
    sides.enter("(teardown)", "");
    instance.reset();
    info.validation = o.validation;
    for (ValidationMessage& m : validation.take()) outside.push_back(std::move(m));
    for (const ValidationMessage& m : outside) {
        std::fprintf(stderr, "validation: %s: %s\n", m.scope.c_str(), format_message(m).c_str());
        info.validation_outside.push_back(m.scope + ": " + format_message(m));
    }
    if (!o.json.empty()) write_json(o.json, info, results, "");
    if (!o.junit.empty()) write_junit(o.junit, info, results);
    if (!o.log.empty()) write_log(o.log, info, results);
    size_t ns =
        std::count_if(results.begin(), results.end(), [](auto& r) { return r.status == Status::kNotSupported; });
    size_t xf =
        std::count_if(results.begin(), results.end(), [](auto& r) { return r.status == Status::kExpectedFail; });
    std::printf("tilevk-cts: %zu passed, %d failed, %zu not supported%s\n", results.size() - fails - ns - xf, fails, ns,
                xf ? (", " + std::to_string(xf) + " known differences (expectations.txt)").c_str() : "");
    if (o.validation) {
        std::map<std::string, int> totals = validation.totals();
        std::string counts;
        for (const std::string& side : {sides.ours, sides.ref})
            counts += (counts.empty() ? "" : ", ") + side + " " + std::to_string(totals[side]);
        for (const auto& [device, n] : totals)
            if (device != sides.ours && device != sides.ref) counts += ", " + device + " " + std::to_string(n);
        std::printf("tilevk-cts: validation messages: %s; %zu outside any case\n", counts.c_str(), outside.size());
    }
    return fails || !outside.empty() ? 1 : 0;
}
