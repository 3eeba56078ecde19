#include "expectations.hpp"

#include <fstream>

namespace tilevk::cts {
namespace {

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

}  // namespace

bool load_expectations(const std::string& path, std::map<std::string, Expectation>* out, std::string* error) {
    std::ifstream in(path);
    if (!in) {
        *error = "cannot read " + path;
        return false;
    }
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const size_t hash = line.find('#');
        const std::string body = trim(line.substr(0, hash));
        if (body.empty()) continue;
        const std::string where = path + ":" + std::to_string(n) + ": ";
        const size_t comma = body.find(',');
        if (comma == std::string::npos) {
            *error = where + "expected CASE,Fail or CASE:PLANE,ReferenceDefect";
            return false;
        }
        std::string name = trim(body.substr(0, comma));
        const std::string kind = trim(body.substr(comma + 1));
        Expectation e;
        e.reason = hash == std::string::npos ? std::string() : trim(line.substr(hash + 1));
        if (e.reason.empty()) {
            *error = where + "every known difference needs its reason after '#'";
            return false;
        }
        if (kind == "Fail") {
            e.kind = Expectation::kFail;
        } else if (kind == "ReferenceDefect") {
            const size_t colon = name.find(':');
            if (colon == std::string::npos) {
                *error = where + "ReferenceDefect names a plane: CASE:PLANE,ReferenceDefect";
                return false;
            }
            e.kind = Expectation::kReferenceDefect;
            e.plane = name.substr(colon + 1);
            name = name.substr(0, colon);
        } else {
            *error = where + "unknown expectation '" + kind + "' (Fail, ReferenceDefect)";
            return false;
        }
        if (!out->emplace(name, e).second) {
            *error = where + name + " is listed twice";
            return false;
        }
    }
    return true;
}

}  // namespace tilevk::cts
