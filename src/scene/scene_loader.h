// Loading JSON scene files (docs/scene_format.md) into a validated SceneDesc.
#pragma once

#include "scene/scene_desc.h"

#include <string>

namespace haif {

/// Reads and validates the scene file at `path`. On failure returns false, leaves `out` untouched and
/// sets `error` to one line: "FILE:LINE:COL: PLACE: what is wrong" (or "FILE: cannot open scene file (...)").
bool loadSceneFile(const std::string& path, SceneDesc& out, std::string& error);

/// Same for scene text already in memory; `pathForMessages` names it in errors, gives the default
/// scene name (its stem) and the directory that asset paths are relative to.
bool parseSceneText(const std::string& text, const std::string& pathForMessages, SceneDesc& out, std::string& error);

/// Empty when `name` may name a scene (and its default output folder output/<name>); else why not.
/// A name is one plain file name: not empty, not "." or "..", no '/' or '\\', no control characters.
std::string sceneNameProblem(const std::string& name);

}  // namespace haif
