// Writes RGBA8 images as PNG with libpng (failure images: ours, ref, diff).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tilevk::cts {

// Returns false (and leaves no partial file) if the file cannot be written.
bool write_png(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba);

}  // namespace tilevk::cts
