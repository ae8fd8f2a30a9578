#pragma once
//! \file report_three_js.h
//! three.js, the WebGL library of the report page (apps/report_html.h), as compiled into the
//! program: cmake/three_js.cmake fetches a pinned release from the npm registry at build time and
//! generates the definitions (<build>/generated/apps/report_three_js.cpp).

#include <string>

namespace delmesh::app {

//! The text of three.js's ES module build (three.module.min.js, with its MIT license header);
//! empty when the program was built without it.
std::string three_js_module();
//! The npm version embedded, e.g. "0.170.0"; empty when none is.
std::string three_js_version();
//! Why three.js is missing, e.g. "built without three.js (npm was not found at configure
//! time)"; empty when it is embedded.
std::string three_js_unavailable_reason();

}  // namespace delmesh::app
