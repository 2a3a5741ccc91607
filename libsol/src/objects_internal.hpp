// What the scene model and the scene file need of each kind of object
// beyond its geometry (not installed): its checks and its scene-file keys.
// All in objects.cpp, next to the kinds' geometry.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "scene_reader.hpp"
#include "sol/objects.hpp"

namespace sol::detail {

/// The checks of scene object `at` ("objects[2]"), and with `quotient`
/// those of the compact quotient; throws FieldError.
void check_object(const SceneObject& object, const std::string& at, bool quotient);

/// A scene object from its JSON at path `at`.
SceneObject read_object(const json& value, const SceneFileReader& reader, const std::string& at);
/// The JSON of a scene object (read_object reads it back).
json write_object(const SceneObject& object);

}  // namespace sol::detail
