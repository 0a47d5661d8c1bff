// The glTF reader's materials: base colour factors, samplers, and textures decoded once per
// distinct image within the scene's budget.
#include "frontend/scene/gltf_reader.hpp"

#include <algorithm>
#include <functional>

namespace vplkit::gltf_detail {

glm::vec3 reader::albedo_of(int material) const {
  if (material < 0) return glm::vec3(1.0f);
  if (material >= static_cast<int>(model_.materials.size())) fail("material " + std::to_string(material) + " does not exist");
  const std::vector<double>& factor = model_.materials[static_cast<std::size_t>(material)].pbrMetallicRoughness.baseColorFactor;
  if (factor.size() != 4) fail("material " + std::to_string(material) + ": baseColorFactor needs 4 numbers");
  const glm::dvec3 albedo(factor[0], factor[1], factor[2]);
  if (!finite(albedo) || glm::any(glm::lessThan(albedo, glm::dvec3(0.0))) || glm::any(glm::greaterThan(albedo, glm::dvec3(1.0))))
    fail("material " + std::to_string(material) + ": baseColorFactor must be in [0, 1]");
  return glm::vec3(albedo);
}

// A number of a JSON value, or fail.
double reader::number(const tinygltf::Value& value, const std::string& what) const {
  if (!value.IsNumber() || !std::isfinite(value.GetNumberAsDouble())) fail(what + " must be a finite number");
  return value.GetNumberAsDouble();
}

texture_wrap reader::wrap_of(int mode, bool& known) {
  known = true;
  if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return texture_wrap::clamp_to_edge;
  if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return texture_wrap::mirrored_repeat;
  known = mode == TINYGLTF_TEXTURE_WRAP_REPEAT;
  return texture_wrap::repeat;
}

texture_sampler reader::sampler_of(int index) const {
  texture_sampler sampler;  // glTF leaves the filters to the renderer: linear, mipmapped
  if (index < 0) return sampler;
  if (index >= static_cast<int>(model_.samplers.size())) fail("sampler " + std::to_string(index) + " does not exist");
  const tinygltf::Sampler& source = model_.samplers[static_cast<std::size_t>(index)];
  const std::string where = "sampler " + std::to_string(index);
  bool known_s = false, known_t = false;
  sampler.wrap_s = wrap_of(source.wrapS, known_s);
  sampler.wrap_t = wrap_of(source.wrapT, known_t);
  if (!known_s || !known_t) fail(where + ": wrapS and wrapT must be 33071 (CLAMP_TO_EDGE), 33648 (MIRRORED_REPEAT) or 10497 (REPEAT)");
  if (source.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) sampler.mag = texture_filter::nearest;
  else if (source.magFilter != TINYGLTF_TEXTURE_FILTER_LINEAR && source.magFilter != -1) fail(where + ": magFilter must be 9728 (NEAREST) or 9729 (LINEAR)");
  switch (source.minFilter) {
    case -1: break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST: sampler.min = texture_filter::nearest; sampler.mipmaps = false; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: sampler.mipmaps = false; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: sampler.min = sampler.between_levels = texture_filter::nearest; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: sampler.between_levels = texture_filter::nearest; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: sampler.min = texture_filter::nearest; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: break;
    default: fail(where + ": minFilter " + std::to_string(source.minFilter) + " is not a GL minification filter");
  }
  return sampler;
}

// The encoded bytes of image `index`: from its buffer view (bounds checked) or as tinygltf read
// its URI; both stay in memory while the model is read (they are not copied).
std::string_view reader::bytes_of_image(int index, const std::string& what) const {
  const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
  if (image.bufferView >= 0) {
    if (image.bufferView >= static_cast<int>(model_.bufferViews.size())) fail(what + ": buffer view " + std::to_string(image.bufferView) + " does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(image.bufferView)];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size())) fail(what + ": buffer " + std::to_string(view.buffer) + " does not exist");
    const std::vector<unsigned char>& data = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) fail(what + ": its buffer view lies outside its buffer");
    return std::string_view(reinterpret_cast<const char*>(data.data() + view.byteOffset), view.byteLength);
  }
  const auto found = images_.find(index);
  if (found == images_.end()) fail(what + ": its file '" + image.uri + "' could not be read (missing, not a regular file, or over the size limit)");
  return found->second;
}

// Image `index` decoded into the library, or fail naming it. Each distinct content is decoded
// once: images that name one file (or carry the same bytes) share its texture, so a file named
// by four images costs one decode and one budget share, not four.
int reader::texture_of(int index) {
  if (index < 0 || index >= static_cast<int>(model_.images.size())) fail("image " + std::to_string(index) + " does not exist");
  int& cached = texture_of_[static_cast<std::size_t>(index)];
  if (cached != unread) return cached;
  const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
  const std::string what = "image " + std::to_string(index) + (image.name.empty() ? "" : " '" + image.name + "'") + (image.uri.empty() || image.uri.rfind("data:", 0) == 0 ? "" : " (" + image.uri + ")");
  const std::string_view bytes = bytes_of_image(index, what);
  const auto [first, last] = texture_of_bytes_.equal_range(std::hash<std::string_view>{}(bytes));
  for (auto same = first; same != last; ++same)
    if (same->second.first == bytes) return cached = same->second.second;
  cached = texture_budget_.decode_into(library_, bytes, name_ + ": " + what, what, limits_.textures);
  texture_of_bytes_.emplace(std::hash<std::string_view>{}(bytes), std::make_pair(bytes, cached));
  return cached;
}

// The TEXCOORD set a texture slot reads: its texCoord, or KHR_texture_transform's; -1 for a
// number outside [0, 7] (refused by the caller; a double beyond int's range must not be cast).
int reader::texcoord_set_of(const tinygltf::TextureInfo& info, const std::string& where) const {
  const auto transform = info.extensions.find("KHR_texture_transform");
  if (transform != info.extensions.end() && transform->second.IsObject() && transform->second.Has("texCoord")) {
    const double set = number(transform->second.Get("texCoord"), where + " KHR_texture_transform texCoord");
    return set >= 0.0 && set <= 7.0 ? static_cast<int>(set) : -1;
  }
  return info.texCoord;
}

// A texture slot of a material (baseColorTexture, emissiveTexture) read the one way for both:
// its image decoded into the library, its sampler, its KHR_texture_transform. `slot` names it in
// messages; `without` is what a texture without a readable image leaves (a note's consequence).
reader::texture_slot reader::texture_slot_of(const tinygltf::TextureInfo& info, const std::string& where, const std::string& slot,
                                             const std::string& without) {
  texture_slot out;
  if (info.index < 0) return out;
  out.texcoord_set = texcoord_set_of(info, where + " " + slot);  // the message names the slot
  if (info.index >= static_cast<int>(model_.textures.size())) fail(where + ": " + slot + " names texture " + std::to_string(info.index) + ", which does not exist");
  const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(info.index)];
  if (texture.source < 0) {
    std::string in;
    for (const auto& [extension, value] : texture.extensions) in += (in.empty() ? "" : ", ") + extension;
    note("texture images given only by " + (in.empty() ? std::string("no source") : in), without);
  } else if (out.texcoord_set < 0 || out.texcoord_set > 7) {
    fail(where + ": " + slot + "'s texCoord must be in [0, 7]");
  } else {
    out.texture = texture_of(texture.source);
    out.sampler = sampler_of(texture.sampler);
  }
  const auto transform = info.extensions.find("KHR_texture_transform");
  if (transform != info.extensions.end() && transform->second.IsObject()) {
    const tinygltf::Value& t = transform->second;
    const std::string in = where + " " + slot + " KHR_texture_transform";
    glm::dvec2 offset(0.0), scale(1.0);
    double rotation = 0.0;
    for (const auto& [key, target] : {std::pair<const char*, glm::dvec2*>{"offset", &offset}, {"scale", &scale}}) {
      if (!t.Has(key)) continue;
      const tinygltf::Value& pair = t.Get(key);
      if (!pair.IsArray() || pair.ArrayLen() != 2) fail(in + ": " + key + " needs 2 numbers");
      *target = glm::dvec2(number(pair.Get(0), in + " " + key), number(pair.Get(1), in + " " + key));
    }
    if (t.Has("rotation")) rotation = number(t.Get("rotation"), in + " rotation");
    // The extension's matrix: translation x rotation x scale, the rotation counter-clockwise
    // in the image (v points down): [cos sin; -sin cos].
    const double c = std::cos(rotation), s = std::sin(rotation);
    const glm::dmat2 rotate(glm::dvec2(c, -s), glm::dvec2(s, c));  // columns
    const glm::dmat2 matrix = rotate * glm::dmat2(glm::dvec2(scale.x, 0.0), glm::dvec2(0.0, scale.y));
    out.matrix = glm::mat2(matrix);
    out.offset = glm::vec2(offset);
    if (!std::isfinite(out.matrix[0][0] + out.matrix[0][1] + out.matrix[1][0] + out.matrix[1][1]) || !std::isfinite(out.offset.x + out.offset.y))
      fail(in + ": the transform is not finite as floats");
  }
  return out;
}

// emissiveFactor x KHR_materials_emissive_strength, checked: the factor in [0, 1] as glTF
// specifies it, the strength finite and >= 0, their product within max_emission.
glm::vec3 reader::emission_of(const tinygltf::Material& source, const std::string& where) const {
  const std::vector<double>& factor = source.emissiveFactor;
  if (factor.empty()) return glm::vec3(0.0f);
  if (factor.size() != 3) fail(where + ": emissiveFactor needs 3 numbers, it has " + std::to_string(factor.size()));
  const glm::dvec3 emissive(factor[0], factor[1], factor[2]);
  if (!finite(emissive) || glm::any(glm::lessThan(emissive, glm::dvec3(0.0))) || glm::any(glm::greaterThan(emissive, glm::dvec3(1.0))))
    fail(where + ": emissiveFactor must be 3 finite numbers in [0, 1], not [" + number_text(factor[0]) + ", " + number_text(factor[1]) + ", " +
         number_text(factor[2]) + "]");
  double strength = 1.0;
  const auto extension = source.extensions.find("KHR_materials_emissive_strength");
  if (extension != source.extensions.end() && extension->second.IsObject() && extension->second.Has("emissiveStrength")) {
    const tinygltf::Value& value = extension->second.Get("emissiveStrength");
    if (!value.IsNumber() || !(value.GetNumberAsDouble() >= 0.0) || !std::isfinite(value.GetNumberAsDouble()))
      fail(where + ": KHR_materials_emissive_strength's emissiveStrength must be a finite number >= 0" +
           (value.IsNumber() ? ", not " + number_text(value.GetNumberAsDouble()) : std::string()));
    strength = value.GetNumberAsDouble();
  }
  const glm::dvec3 emission = emissive * strength;
  if (glm::any(glm::greaterThan(emission, glm::dvec3(max_emission))))
    fail(where + ": emissiveFactor x emissiveStrength must be at most " + number_text(max_emission) + " per channel (the largest radiance a 16-bit float image holds), not " +
         number_text(std::max({emission.x, emission.y, emission.z})));
  return glm::vec3(emission);
}

reader::material_use reader::material_for(int index) {
  if (index < 0) return {};
  int& cached = material_of_[static_cast<std::size_t>(index)];
  if (cached != unread) return {cached, texcoord_set_of_[static_cast<std::size_t>(index)]};
  const tinygltf::Material& source = model_.materials[static_cast<std::size_t>(index)];
  const std::string where = "material " + std::to_string(index) + (source.name.empty() ? "" : " '" + source.name + "'");
  surface_material made;
  made.name = source.name;
  const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
  if (factor.size() == 4) {
    if (!(factor[3] >= 0.0 && factor[3] <= 1.0)) fail(where + ": baseColorFactor's alpha must be in [0, 1]");
    made.alpha_factor = static_cast<float>(factor[3]);
  }
  if (source.alphaMode == "MASK") {
    if (!(source.alphaCutoff >= 0.0 && std::isfinite(source.alphaCutoff))) fail(where + ": alphaCutoff must be a finite number >= 0");
    made.alpha_mask = true;
    made.alpha_cutoff = static_cast<float>(std::min(source.alphaCutoff, 1.0));
  } else if (source.alphaMode != "OPAQUE" && source.alphaMode != "BLEND") {
    fail(where + ": alphaMode must be OPAQUE, MASK or BLEND, not '" + source.alphaMode + "'");
  }
  const texture_slot base = texture_slot_of(source.pbrMetallicRoughness.baseColorTexture, where, "baseColorTexture",
                                            "those textures are left out: their factor alone is the albedo");
  made.texture = base.texture;
  made.sampler = base.sampler;
  made.texture_matrix = base.matrix;
  made.texture_offset = base.offset;
  made.emission = emission_of(source, where);
  if (emits(made)) {
    texture_slot emission = texture_slot_of(source.emissiveTexture, where, "emissiveTexture", "those textures are left out: their factor alone is the emission");
    // A vertex carries one texture coordinate: the emission texture reads the base colour's set
    // or, without a base colour texture, its own.
    if (emission.texture >= 0 && made.texture >= 0 && emission.texcoord_set != base.texcoord_set) {
      note("emissiveTexture on another TEXCOORD set than its baseColorTexture", "those emission textures are left out: their factor alone is the emission");
      emission.texture = -1;
    }
    made.emission_texture = emission.texture;
    made.emission_sampler = emission.sampler;
    made.emission_texture_matrix = emission.matrix;
    made.emission_texture_offset = emission.offset;
  }
  const int texcoord_set = made.texture >= 0 ? base.texcoord_set : made.emission_texture >= 0 ? texcoord_set_of(source.emissiveTexture, where + " emissiveTexture") : -1;
  texcoord_set_of_[static_cast<std::size_t>(index)] = texcoord_set;
  if (made.texture < 0 && !made.alpha_mask && !emits(made)) {
    cached = -1;  // plain: the factor alone, opaque, not emitting
    return {};
  }
  library_.materials.push_back(std::move(made));
  cached = static_cast<int>(library_.materials.size() - 1);
  return {cached, texcoord_set};
}

}  // namespace vplkit::gltf_detail
