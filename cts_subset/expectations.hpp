// The conformance subset's known differences (expectations.txt), as Mesa's CI keeps them: one line per case,
//   CASE,Fail # reason                  the case is expected to fail (a named difference or a lavapipe defect)
//   CASE:PLANE,ReferenceDefect # reason  the reference is known wrong in that read-back plane: not compared
// The runner reads the file instead of exceptions written into the cases.
#pragma once

#include <map>
#include <string>

namespace tilevk::cts {

struct Expectation {
    enum Kind { kFail, kReferenceDefect } kind = kFail;
    std::string plane;  // kReferenceDefect
    std::string reason;
};

// Case name -> its expectation. False (with *error naming the line) for a malformed file or a case listed twice.
bool load_expectations(const std::string& path, std::map<std::string, Expectation>* out, std::string* error);

}  // namespace tilevk::cts
