#pragma once
// Writes scenes back to glTF 2.0 with KHR_lights_punctual, in two ways: a
// new self-contained file from a scene (gltf_scene_writer.h), or an existing
// file with its lights replaced (gltf_light_patcher.h). The output's format
// follows its extension: .glb is binary, anything else is .gltf JSON with
// base64-embedded buffers; files are written to a temporary name first and
// renamed, so a failed write never leaves half a file (gltf_document_output.h).
//
// Each light gets its own node (position as translation, direction as the
// rotation taking -Z onto it) carrying extras.lightcuts_guid, so the loader
// gives it back the same GUID, and extras.lightcuts_classic when classic
// (gltf_light_json.h).
#include "editor_client/scene/gltf/writer/gltf_light_patcher.h"
#include "editor_client/scene/gltf/writer/gltf_scene_writer.h"
