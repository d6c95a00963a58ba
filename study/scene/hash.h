// The content hash of a Scene: SHA-256 of a canonical text serialization.
// Guarantee: identical on every machine for the same scene. Floats are
// written as integers of 1e-4 units (llround), and only values that the
// generators compute with IEEE-754 basic operations and sqrt (bit-identical
// everywhere) are serialized: transforms, colours, answer, plan, camera pose.
// Values that go through sin/cos (mesh vertices, the orbit distance, near
// and far planes) are never serialized; meshes appear as name + vertex and
// triangle counts + kSceneFormatVersion, the orbit distance as fov_y.
#pragma once
#include <string>

#include "study/scene/scene.h"

namespace dtlab::scene {

// Bump when the serialization or any mesh's tessellation changes, so old
// hashes no longer match scenes that would now look different.
inline constexpr int kSceneFormatVersion = 1;

std::string canonical_serialization(const Scene& scene);  // one line per item, '\n' separated, ASCII
std::string scene_hash(const Scene& scene);               // sha256_hex(canonical_serialization(scene))

}  // namespace dtlab::scene
