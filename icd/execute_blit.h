// vkCmdBlitImage: recorded here, executed by rast/render/blit.h (lavapipe 22.3's blit, icd/README.md "Blits").
#pragma once
#include "commands.h"
#include "formats.h"

namespace tilevk::icd {

struct ExecState;

// Checks each VkImageBlit region against its images (invalid usage is skipped with a message, never a crash) and
// hands it to rast::render::blit on the queue's worker threads.
void exec_blit_image(ExecState& st, const CmdBlitImage& c);

// True if the format can be a blit source (`source`: BLIT_SRC) or destination (BLIT_DST).
bool blit_supported(const FormatInfo& f, bool source);

}  // namespace tilevk::icd
