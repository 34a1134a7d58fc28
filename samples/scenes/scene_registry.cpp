// The scene names and makeScene(): every scene file's factory (scene_registry.hpp) by name.
#include "scene_registry.hpp"

#include <stdexcept>

namespace gdc::scenes {

std::vector<std::string> sceneNames() { return {"box_drop", "tower", "brick_wall", "composites", "big_world"}; }

std::vector<std::string> extraSceneNames() { return {"barrels", "terrain"}; }

std::vector<std::string> allSceneNames() {
    std::vector<std::string> names = sceneNames();
    for (std::string& name : extraSceneNames()) names.push_back(std::move(name));
    return names;
}

std::unique_ptr<Scene> makeScene(const std::string& name, const SceneOptions& options) {
    std::unique_ptr<Scene> scene;
    if (name == "box_drop") scene = makeBoxDrop(options);
    else if (name == "tower") scene = makeTower(options);
    else if (name == "brick_wall") scene = makeBrickWall(options);
    else if (name == "composites") scene = makeComposites(options);
    else if (name == "big_world") scene = makeBigWorld(options);
    else if (name == "barrels") scene = makeBarrels(options);
    else if (name == "terrain") scene = makeTerrain(options);
    else throw std::invalid_argument("unknown scene '" + name +
                                     "' (box_drop, tower, brick_wall, composites, big_world, barrels, terrain)");
    scene->reset();
    return scene;
}

}  // namespace gdc::scenes
