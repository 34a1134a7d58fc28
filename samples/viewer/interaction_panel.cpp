// The ImGui side of interaction.hpp: the panel section that chooses what to add and loads OBJ
// files, and the inspector window. Called while the viewer holds the scene lock.
#include "interaction.hpp"

#include <imgui.h>

#include <cmath>
#include <iterator>

namespace gdc::viewer {
namespace {

// + 0.0 turns −0 into 0: a resting body's "-0.000" reads as a sign that means nothing.
void vectorText(const char* label, const Vec3& v, const char* unit) {
    ImGui::Text("%s (%.3f, %.3f, %.3f) %s  |%.3f|", label, v.x() + 0.0, v.y() + 0.0, v.z() + 0.0, unit, v.norm());
}

}  // namespace

void Interaction::panelSection() {
    // Closed at first: the panel is already as tall as a laptop screen; the keys work either way.
    if (!ImGui::CollapsingHeader("add bodies, inspect")) return;
    const char* names[std::size(kSpawnKinds)];
    for (std::size_t i = 0; i < std::size(kSpawnKinds); ++i) names[i] = spawnKindName(kSpawnKinds[i]);
    int chosen = int(kind);
    if (ImGui::Combo("adds", &chosen, names, int(std::size(names)))) kind = kSpawnKinds[chosen];
    float speed = float(throwSpeed), mass = float(density);
    // Up to 40 m/s, the cap viewer.cpp puts on a flick too (kFastestThrow).
    if (ImGui::SliderFloat("throw speed", &speed, 1.0f, 40.0f, "%.1f m/s")) throwSpeed = speed;
    if (ImGui::SliderFloat("density", &mass, 100.0f, 8000.0f, "%.0f kg/m3", ImGuiSliderFlags_Logarithmic)) density = mass;

    ImGui::InputText("OBJ file", objPath_, sizeof objPath_);
    ImGui::Checkbox("one hull", &objAsHull_);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(80);
    ImGui::InputFloat("scale", &objScale_, 0.0f, 0.0f, "%.3g");
    ImGui::SameLine();
    if (ImGui::Button("load"))
        loadObj(objPath_, objAsHull_ ? scenes::ObjLayout::Hull : scenes::ObjLayout::PartPerObject, objScale_);
    if (!objStatus_.empty()) {
        if (objFailed_) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s", objStatus_.c_str());
        if (objFailed_) ImGui::PopStyleColor();
    }

    ImGui::Checkbox("inspector", &inspector);
    ImGui::SameLine();
    ImGui::Checkbox("wireframe", &debug.wireframe);
    ImGui::SameLine();
    ImGui::Checkbox("bounds", &debug.bounds);
    ImGui::TextDisabled("d drop at cursor  t throw  1-6 kind");
    ImGui::TextDisabled("shift+right-drag: throw by flick");
    ImGui::TextDisabled("i inspector  w wireframe  b bounds");
}

void Interaction::inspectorWindow(const scenes::Scene* scene, const SceneShapes& shapes, const OrbitCamera& camera,
                                  double x, double y, int width, int height, const std::string& view) const {
    // At the window's right edge, below where a view's method and verdict are written (side by
    // side, the right view's), whichever view is inspected.
    ImGui::SetNextWindowPos(ImVec2(ImGui::GetIO().DisplaySize.x - 410.0f, 100.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(400.0f, 0.0f), ImGuiCond_FirstUseEver);
    ImGui::Begin("inspector");
    if (scene == nullptr) {
        ImGui::TextDisabled("the cursor is on no view");
        ImGui::End();
        return;
    }
    if (!view.empty()) ImGui::TextDisabled("%s", view.c_str());
    const auto inspection = inspectAlong(*scene, shapes, camera.rayThroughPixel(x, y, width, height));
    if (!inspection) {
        ImGui::TextDisabled("no body under the cursor");
    } else {
        ImGui::Text("%s   mass %.4g kg", inspection->name.c_str(), inspection->mass);
        vectorText("x", inspection->position, "m");
        vectorText("v", inspection->linearVelocity, "m/s");
        vectorText("w", inspection->angularVelocity, "rad/s");
        ImGui::Text("%zu contacts in the last step", inspection->contacts.size());
        if (!inspection->contacts.empty() && ImGui::BeginTable("contacts", 3, ImGuiTableFlags_Borders)) {
            ImGui::TableSetupColumn("depth (mm)");
            ImGui::TableSetupColumn("normal (into it)");
            ImGui::TableSetupColumn("with");
            ImGui::TableHeadersRow();
            for (const InspectedContact& c : inspection->contacts) {
                ImGui::TableNextRow();
                ImGui::TableNextColumn();
                ImGui::Text("%.3f", c.depth * 1e3);
                ImGui::TableNextColumn();
                ImGui::Text("%.2f %.2f %.2f", c.normal.x() + 0.0, c.normal.y() + 0.0, c.normal.z() + 0.0);
                ImGui::TableNextColumn();
                ImGui::TextUnformatted(c.other.c_str());
            }
            ImGui::EndTable();
        }
    }
    // A contact drawn within 10 pixels of the cursor: the one a person is pointing at.
    if (const auto contact = contactNearPixel(*scene, camera, x, y, width, height, 10.0)) {
        ImGui::Separator();
        ImGui::Text("contact under the cursor: depth %.3f mm", contact->depth * 1e3);
        vectorText("at", contact->position, "m");
        vectorText("n", contact->normal, "");
    }
    ImGui::End();
}

}  // namespace gdc::viewer
