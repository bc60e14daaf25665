# achd_case_json: the case parser and result writer (case_json.cpp) with what it uses (the
# JSON reader that refuses duplicate keys, the printable names of messages, the marks of
# a JS caller's values JSON cannot hold). One list, built by the CLI (tools/), the wasm
# module (wasm/), whose JS solve() parses its cases here too, and the fuzzers (fuzz/).
# Needs the targets achd and nlohmann_json::nlohmann_json.
set(_achd_case_dir ${CMAKE_CURRENT_LIST_DIR})
add_library(achd_case_json STATIC ${_achd_case_dir}/case_json.cpp ${_achd_case_dir}/json_text.cpp
            ${_achd_case_dir}/printable.cpp ${_achd_case_dir}/foreign_values.cpp
            ${_achd_case_dir}/loops_json.cpp)
target_include_directories(achd_case_json PUBLIC ${_achd_case_dir})
target_link_libraries(achd_case_json PUBLIC achd nlohmann_json::nlohmann_json)
