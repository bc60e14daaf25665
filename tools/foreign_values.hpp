#pragma once
// Values of a JS caller that JSON cannot hold (undefined, NaN, a Map, a getter, ...), on
// their way to the case parser. The wasm module's bridge (wasm/js/json_text.mjs) writes
// each as a JSON string: a NUL, "achd:", then what the value was ("a Map", "undefined",
// "NaN"). mark_foreign() turns those strings into binary JSON values, which no JSON text
// can make, so that a case file never holds one and the parser tells them apart from
// everything a file can hold: each check that refuses a value ends its message with what
// it was (got(): ", got a Map"), a number that was NaN or +-Infinity "is not finite" as
// in a file, and an optional field given undefined is absent, as in JS (a required one is
// there, with a value of the wrong kind).
#include <string>

#include <nlohmann/json.hpp>

namespace achd::cli {

// Replaces, everywhere inside `value`, each string the bridge wrote for a foreign value
// by a binary value holding what it was.
void mark_foreign(nlohmann::json& value);

// ", got a Map" for a foreign value, "" for anything a JSON text holds (for those the
// message is the CLI's word for word).
std::string got(const nlohmann::json& value);

// A JS number that is NaN, Infinity or -Infinity.
bool non_finite(const nlohmann::json& value);

// `object` has `key` with a value other than JS's undefined.
bool given(const nlohmann::json& object, const char* key);

}  // namespace achd::cli
