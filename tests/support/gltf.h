// SPDX-License-Identifier: MIT
// Small glTF 2.0 files built in code for tests and fuzz seeds: one binary buffer, accessors added
// one by one, the document as JSON, written as .gltf (buffer embedded as a data URI, or in a .bin
// beside it) or as .glb.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace inkline::test {

class GltfBuilder {
  public:
    GltfBuilder();

    // Appends raw bytes as a bufferView (4-byte aligned); returns its index.
    int view(const void* data, size_t bytes, size_t stride = 0);
    // An accessor over a view: glTF component type (5126 float, 5121 ubyte ...) and type name.
    int accessor(int view, int component_type, size_t count, const std::string& type, bool normalized = false);
    int floats(const std::vector<float>& values, const std::string& type);
    int indices(const std::vector<uint32_t>& values);

    // A node with a mesh of one triangle-list primitive; returns the node index. Extra
    // primitive attributes and targets may be added to json() afterwards.
    int mesh_node(const std::string& name, const std::vector<float>& positions, const std::vector<uint32_t>& indices);
    // A node without mesh; returns its index.
    int node(const std::string& name);
    void add_child(int parent, int child);
    // Makes the scene's roots every node that is no child.
    void finish_scene();

    nlohmann::json& json() { return doc_; }
    const std::vector<uint8_t>& buffer() const { return bin_; }

    std::string gltf_text() const;           // buffer as a base64 data URI
    std::vector<uint8_t> glb() const;        // binary container
    // Writes by extension: .glb, or .gltf with the buffer embedded (or, with bin_name, beside it).
    void write(const std::filesystem::path& path, const std::string& bin_name = "") const;

  private:
    nlohmann::json doc_;
    std::vector<uint8_t> bin_;
};

}  // namespace inkline::test
