// A case's outcome and the writers for the CTS-style text log, JUnit XML and the JSON the report reads.
#pragma once

#include <string>
#include <vector>

namespace tilevk::cts {

// kExpectedFail: a failure expectations.txt lists (a known difference), not counted as a failure.
enum class Status { kPass, kFail, kNotSupported, kExpectedFail };
const char* status_name(Status s);

struct CaseResult {
    std::string name;
    std::string note;
    Status status = Status::kPass;
    std::string reason;
    uint64_t differing = 0, total = 0;  // pixels over every plane
    double max_error = 0;
    std::string check;                 // "none", or the independent check's verdict ("ok" / failure text)
    std::string oracle = "none";       // coverage oracle: "none", "n/a: why", "ok (...)" or the disagreement
    double ours_ms = -1, ref_ms = -1;  // median frame time, -1 if not timed
    double ours_pipeline_ms = -1, ref_pipeline_ms = -1;
    double seconds = 0;                   // wall time of the whole case
    std::vector<std::string> validation;  // --validation: the layer's messages during the case, "[device] ..."
};

struct RunInfo {
    std::string device, ref, device_name, ref_name, rast_method, icd_filenames;
    bool device_found = false;
    int timing_reps = 0;
    std::string threads;
    bool validation = false;                      // --validation was on
    std::vector<std::string> validation_outside;  // messages outside any case (device creation, teardown)
};

std::string json_escape(const std::string& s);
bool write_json(const std::string& path, const RunInfo& info, const std::vector<CaseResult>& results,
                const std::string& running);
bool write_junit(const std::string& path, const RunInfo& info, const std::vector<CaseResult>& results);
bool write_log(const std::string& path, const RunInfo& info, const std::vector<CaseResult>& results);

}  // namespace tilevk::cts
