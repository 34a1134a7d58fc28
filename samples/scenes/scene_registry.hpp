// The factories behind makeScene(), one per scene file. Private to samples/scenes.
#pragma once

#include "scene.hpp"

namespace gdc::scenes {

std::unique_ptr<Scene> makeBoxDrop(const SceneOptions& options);
std::unique_ptr<Scene> makeTower(const SceneOptions& options);
std::unique_ptr<Scene> makeBrickWall(const SceneOptions& options);
std::unique_ptr<Scene> makeComposites(const SceneOptions& options);
std::unique_ptr<Scene> makeBigWorld(const SceneOptions& options);
std::unique_ptr<Scene> makeBarrels(const SceneOptions& options);
std::unique_ptr<Scene> makeTerrain(const SceneOptions& options);

}  // namespace gdc::scenes
