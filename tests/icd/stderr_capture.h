// What the process writes to stderr (fd 2, where tilevk reports refusals and device loss), captured for tests
// that check a message names the right Vulkan thing.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <functional>
#include <string>

namespace tilevk::test {

// Redirects fd 2 into a temporary file while it lives; text() ends the capture and returns what was written.
class StderrCapture {
  public:
    StderrCapture() {
        std::fflush(stderr);
        file_ = std::tmpfile();
        if (file_ == nullptr) return;
        saved_ = dup(2);
        dup2(fileno(file_), 2);
    }
    ~StderrCapture() {
        restore();
        if (file_ != nullptr) std::fclose(file_);
    }
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;

    std::string text() {
        restore();
        std::string out;
        if (file_ == nullptr) return out;
        std::rewind(file_);
        char buf[4096];
        for (size_t n; (n = std::fread(buf, 1, sizeof buf, file_)) > 0;) out.append(buf, n);
        return out;
    }

  private:
    void restore() {
        if (saved_ < 0) return;
        std::fflush(stderr);
        dup2(saved_, 2);
        close(saved_);
        saved_ = -1;
    }
    std::FILE* file_ = nullptr;
    int saved_ = -1;
};

// What is written to stderr while `fn` runs.
inline std::string stderr_of(const std::function<void()>& fn) {
    StderrCapture capture;
    fn();
    return capture.text();
}

}  // namespace tilevk::test
