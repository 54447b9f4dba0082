#pragma once
// The page of `pierce report`: the template of render/report/ (report.html, report.css,
// report.js) with three.js r111 and its OrbitControls, embedded in the binary at build time
// (apps/CMakeLists.txt, cmake/EmbedText.cmake), filled with a report's data.
#include <string>

#include <nlohmann/json.hpp>

namespace pierce::cli {

// One self-contained HTML document: the style sheet and every script inlined, `data` as JSON in
// a <script type="application/json"> element (with "</" written "<\/", so no text in it can end
// the element), `title` HTML-escaped.
std::string report_page(const std::string& title, const nlohmann::ordered_json& data);

}  // namespace pierce::cli
