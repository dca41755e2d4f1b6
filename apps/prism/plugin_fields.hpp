// `prism plugin fields`: the JSON fields of primitive plugins, from their own
// PrismField tables. The Markdown form is the table of docs/scene-format.md
// (between its `fields:begin` and `fields:end` markers), so the docs follow
// the plugins instead of being written twice; a CTest test compares them.
#pragma once

#include <string>
#include <vector>

#include "prism/primitive_abi.h"

namespace prism::cli {

// One Markdown table for every plugin, in the order given: a row per field,
// and one for `center` and `rotation` where the type takes them.
std::string fields_markdown(const std::vector<const PrismPrimitiveDesc*>& plugins);

// One line per field: name, kind, required or default, range, doc.
std::string fields_text(const PrismPrimitiveDesc& plugin);

}  // namespace prism::cli
