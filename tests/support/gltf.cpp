// SPDX-License-Identifier: MIT
#include "tests/support/gltf.h"

#include <cstring>
#include <fstream>
#include <set>

namespace inkline::test {
namespace {

std::string base64(const std::vector<uint8_t>& bytes) {
    static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const uint32_t b0 = bytes[i], b1 = i + 1 < bytes.size() ? bytes[i + 1] : 0, b2 = i + 2 < bytes.size() ? bytes[i + 2] : 0;
        const uint32_t v = (b0 << 16) | (b1 << 8) | b2;
        out += kDigits[(v >> 18) & 63];
        out += kDigits[(v >> 12) & 63];
        out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
        out += i + 2 < bytes.size() ? kDigits[v & 63] : '=';
    }
    return out;
}

void put32(std::vector<uint8_t>& out, uint32_t v) {
    for (int k = 0; k < 4; ++k) out.push_back(uint8_t(v >> (8 * k)));
}

}  // namespace

GltfBuilder::GltfBuilder() {
    doc_ = {{"asset", {{"version", "2.0"}}},
            {"scenes", nlohmann::json::array({nlohmann::json::object({{"nodes", nlohmann::json::array()}})})},
            {"scene", 0},
            {"nodes", nlohmann::json::array()},
            {"meshes", nlohmann::json::array()},
            {"accessors", nlohmann::json::array()},
            {"bufferViews", nlohmann::json::array()}};
}

int GltfBuilder::view(const void* data, size_t bytes, size_t stride) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    const size_t offset = bin_.size();
    bin_.resize(offset + bytes);
    std::memcpy(bin_.data() + offset, data, bytes);
    nlohmann::json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    if (stride) v["byteStride"] = stride;
    doc_["bufferViews"].push_back(v);
    return int(doc_["bufferViews"].size()) - 1;
}

int GltfBuilder::accessor(int view, int component_type, size_t count, const std::string& type, bool normalized) {
    nlohmann::json a = {{"componentType", component_type}, {"count", count}, {"type", type}};
    if (view >= 0) a["bufferView"] = view;
    if (normalized) a["normalized"] = true;
    doc_["accessors"].push_back(a);
    return int(doc_["accessors"].size()) - 1;
}

int GltfBuilder::floats(const std::vector<float>& values, const std::string& type) {
    const size_t width = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
    const int v = view(values.data(), values.size() * sizeof(float));
    const int a = accessor(v, 5126, values.size() / width, type);
    if (type == "VEC3" && !values.empty()) {  // POSITION needs min and max
        std::vector<float> lo(values.begin(), values.begin() + 3), hi = lo;
        for (size_t i = 0; i + 2 < values.size(); i += 3) {
            for (size_t c = 0; c < 3; ++c) {
                lo[c] = std::min(lo[c], values[i + c]);
                hi[c] = std::max(hi[c], values[i + c]);
            }
        }
        doc_["accessors"][size_t(a)]["min"] = lo;
        doc_["accessors"][size_t(a)]["max"] = hi;
    }
    return a;
}

int GltfBuilder::indices(const std::vector<uint32_t>& values) {
    const int v = view(values.data(), values.size() * sizeof(uint32_t));
    return accessor(v, 5125, values.size(), "SCALAR");
}

int GltfBuilder::mesh_node(const std::string& name, const std::vector<float>& positions, const std::vector<uint32_t>& idx) {
    const int pos = floats(positions, "VEC3");
    nlohmann::json prim = {{"attributes", {{"POSITION", pos}}}};
    if (!idx.empty()) prim["indices"] = indices(idx);
    doc_["meshes"].push_back({{"primitives", nlohmann::json::array({prim})}});
    const int n = node(name);
    doc_["nodes"][size_t(n)]["mesh"] = doc_["meshes"].size() - 1;
    return n;
}

int GltfBuilder::node(const std::string& name) {
    doc_["nodes"].push_back({{"name", name}});
    return int(doc_["nodes"].size()) - 1;
}

void GltfBuilder::add_child(int parent, int child) { doc_["nodes"][size_t(parent)]["children"].push_back(child); }

void GltfBuilder::finish_scene() {
    std::set<int> children;
    for (const auto& n : doc_["nodes"]) {
        if (n.contains("children")) {
            for (const auto& c : n["children"]) children.insert(c.get<int>());
        }
    }
    auto& roots = doc_["scenes"][0]["nodes"];
    roots = nlohmann::json::array();
    for (int i = 0; i < int(doc_["nodes"].size()); ++i) {
        if (!children.count(i)) roots.push_back(i);
    }
}

std::string GltfBuilder::gltf_text() const {
    nlohmann::json d = doc_;
    d["buffers"] = {{{"byteLength", bin_.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin_)}}};
    return d.dump();
}

std::vector<uint8_t> GltfBuilder::glb() const {
    nlohmann::json d = doc_;
    d["buffers"] = {{{"byteLength", bin_.size()}}};
    std::string text = d.dump();
    while (text.size() % 4 != 0) text += ' ';
    std::vector<uint8_t> bin = bin_;
    while (bin.size() % 4 != 0) bin.push_back(0);
    std::vector<uint8_t> out;
    put32(out, 0x46546C67);  // "glTF"
    put32(out, 2);
    put32(out, uint32_t(12 + 8 + text.size() + 8 + bin.size()));
    put32(out, uint32_t(text.size()));
    put32(out, 0x4E4F534A);  // "JSON"
    out.insert(out.end(), text.begin(), text.end());
    put32(out, uint32_t(bin.size()));
    put32(out, 0x004E4942);  // "BIN"
    out.insert(out.end(), bin.begin(), bin.end());
    return out;
}

void GltfBuilder::write(const std::filesystem::path& path, const std::string& bin_name) const {
    std::ofstream out(path, std::ios::binary);
    if (path.extension() == ".glb") {
        const std::vector<uint8_t> bytes = glb();
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        return;
    }
    if (bin_name.empty()) {
        out << gltf_text();
        return;
    }
    nlohmann::json d = doc_;
    d["buffers"] = {{{"byteLength", bin_.size()}, {"uri", bin_name}}};
    out << d.dump();
    std::ofstream(path.parent_path() / bin_name, std::ios::binary)
        .write(reinterpret_cast<const char*>(bin_.data()), std::streamsize(bin_.size()));
}

}  // namespace inkline::test
