#include "results.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace tilevk::cts {

const char* status_name(Status s) {
    switch (s) {
        case Status::kPass:
            return "Pass";
        case Status::kFail:
            return "Fail";
        case Status::kExpectedFail:
            return "ExpectedFail";
        default:
            return "NotSupported";
    }
}

std::string json_escape(const std::string& s) {
    std::string o;
    for (unsigned char c : s) {
        if (c == '"' || c == '\\') {
            o += '\\';
            o += char(c);
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            o += buf;
        } else {
            o += char(c);
        }
    }
    return o;
}

namespace {

// JSON has no inf/nan; Python's json module (the report) reads these spellings.
std::string num(double v) {
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "Infinity" : "-Infinity";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string xml_escape(const std::string& s) {
    std::string o;
    for (char c : s) {
        switch (c) {
            case '<':
                o += "&lt;";
                break;
            case '>':
                o += "&gt;";
                break;
            case '&':
                o += "&amp;";
                break;
            case '"':
                o += "&quot;";
                break;
            default:
                o += (static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') ? ' ' : c;
        }
    }
    return o;
}

std::string json_list(const std::vector<std::string>& items) {
    std::string o = "[";
    for (size_t i = 0; i < items.size(); ++i) o += (i ? ", \"" : "\"") + json_escape(items[i]) + "\"";
    return o + "]";
}

// Writes to a temporary file and renames, so a reader never sees half a file.
bool write_atomically(const std::string& path, const std::string& text) {
    std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary);
        if (!f) return false;
        f << text;
        if (!f) return false;
    }
    return std::rename(tmp.c_str(), path.c_str()) == 0;
}

}  // namespace

bool write_json(const std::string& path, const RunInfo& info, const std::vector<CaseResult>& results,
                const std::string& running) {
    std::ostringstream o;
    o << "{\n  \"device\": \"" << json_escape(info.device) << "\",\n  \"ref\": \"" << json_escape(info.ref)
      << "\",\n  \"device_name\": \"" << json_escape(info.device_name) << "\",\n  \"ref_name\": \""
      << json_escape(info.ref_name) << "\",\n  \"device_found\": " << (info.device_found ? "true" : "false")
      << ",\n  \"rast_method\": \"" << json_escape(info.rast_method) << "\",\n  \"threads\": \""
      << json_escape(info.threads) << "\",\n  \"icd_filenames\": \"" << json_escape(info.icd_filenames)
      << "\",\n  \"timing_reps\": " << info.timing_reps << ",\n  \"complete\": " << (running.empty() ? "true" : "false")
      << ",\n  \"running\": \"" << json_escape(running)
      << "\",\n  \"validation\": " << (info.validation ? "true" : "false")
      << ",\n  \"validation_outside\": " << json_list(info.validation_outside) << ",\n  \"cases\": [\n";
    for (size_t i = 0; i < results.size(); ++i) {
        const CaseResult& r = results[i];
        o << "    {\"name\": \"" << json_escape(r.name) << "\", \"status\": \"" << status_name(r.status)
          << "\", \"reason\": \"" << json_escape(r.reason) << "\", \"note\": \"" << json_escape(r.note)
          << "\", \"differing\": " << r.differing << ", \"total\": " << r.total
          << ", \"max_error\": " << num(r.max_error) << ", \"check\": \"" << json_escape(r.check)
          << "\", \"oracle\": \"" << json_escape(r.oracle) << "\", \"ours_ms\": " << num(r.ours_ms)
          << ", \"ref_ms\": " << num(r.ref_ms) << ", \"ours_pipeline_ms\": " << num(r.ours_pipeline_ms)
          << ", \"ref_pipeline_ms\": " << num(r.ref_pipeline_ms) << ", \"seconds\": " << num(r.seconds)
          << ", \"validation\": " << json_list(r.validation) << "}" << (i + 1 < results.size() ? "," : "") << "\n";
    }
    o << "  ]\n}\n";
    return write_atomically(path, o.str());
}

bool write_junit(const std::string& path, const RunInfo& info, const std::vector<CaseResult>& results) {
    size_t fails = 0, skips = 0;
    double total = 0;
    for (const CaseResult& r : results) {
        fails += r.status == Status::kFail;
        skips += r.status == Status::kNotSupported || r.status == Status::kExpectedFail;
        total += r.seconds;
    }
    std::ostringstream o;
    o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites>\n<testsuite name=\"tilevk-cts\" tests=\""
      << results.size() << "\" failures=\"" << fails << "\" skipped=\"" << skips << "\" time=\"" << num(total)
      << "\">\n  <properties><property name=\"device\" value=\"" << xml_escape(info.device_name)
      << "\"/><property name=\"ref\" value=\"" << xml_escape(info.ref_name) << "\"/></properties>\n";
    for (const CaseResult& r : results) {
        std::string cls = r.name.substr(0, r.name.rfind('.'));
        o << "  <testcase classname=\"" << xml_escape(cls) << "\" name=\"" << xml_escape(r.name) << "\" time=\""
          << num(r.seconds) << "\">";
        if (r.status == Status::kFail)
            o << "<failure message=\"" << xml_escape(r.reason) << "\"/>";
        else if (r.status == Status::kNotSupported || r.status == Status::kExpectedFail)
            o << "<skipped message=\"" << xml_escape(r.reason) << "\"/>";
        o << "</testcase>\n";
    }
    o << "</testsuite>\n</testsuites>\n";
    return write_atomically(path, o.str());
}

bool write_log(const std::string& path, const RunInfo& info, const std::vector<CaseResult>& results) {
    std::ostringstream o;
    size_t n[4] = {0, 0, 0, 0};
    o << "#tilevk-cts device='" << info.device_name << "' ref='" << info.ref_name << "'\n";
    for (const CaseResult& r : results) {
        n[int(r.status)]++;
        o << "Test case '" << r.name << "'..\n";
        if (r.status == Status::kPass)
            o << "  Pass (" << r.total << " pixels equal" << (r.check.empty() || r.check == "none" ? "" : ", check ok")
              << (r.oracle.rfind("ok", 0) == 0 ? ", coverage oracle ok" : "") << ")\n";
        else
            o << "  " << status_name(r.status) << " (" << r.reason << ")\n";
    }
    o << "\nTest run totals:\n  Passed:        " << n[0] << "/" << results.size() << "\n  Failed:        " << n[1]
      << "/" << results.size() << "\n  Not supported: " << n[2] << "/" << results.size()
      << "\n  Expected fail: " << n[3] << "/" << results.size() << "\n";
    return write_atomically(path, o.str());
}

}  // namespace tilevk::cts
