#include "engine/scene/gltf_accessor_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace eng {
namespace {

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
  }
}

std::string prefix(int accessor, std::string_view what) {
  return "accessor " + std::to_string(accessor) + " (" + std::string(what) + ")";
}

template <class Raw>
Raw load(const uint8_t* p) {
  Raw v;
  std::memcpy(&v, p, sizeof(Raw));
  return v;
}

// One component as float, applying the glTF normalization rules.
float componentAsFloat(const uint8_t* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return load<float>(p);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = static_cast<float>(load<int8_t>(p));
      return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const float v = static_cast<float>(load<uint8_t>(p));
      return normalized ? v / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float v = static_cast<float>(load<int16_t>(p));
      return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const float v = static_cast<float>(load<uint16_t>(p));
      return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      const double v = static_cast<double>(load<uint32_t>(p));
      return static_cast<float>(normalized ? v / 4294967295.0 : v);
    }
    case TINYGLTF_COMPONENT_TYPE_INT: {
      const double v = static_cast<double>(load<int32_t>(p));
      return static_cast<float>(normalized ? std::max(v / 2147483647.0, -1.0) : v);
    }
    default: return 0.0f;
  }
}

uint32_t componentAsIndex(const uint8_t* p, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return load<uint8_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return load<uint16_t>(p);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return load<uint32_t>(p);
    default: return 0;
  }
}

// The byte range [offset, offset + size) of a buffer view, checked against its buffer.
struct ViewRange {
  const uint8_t* data = nullptr;
  size_t size = 0;
  size_t stride = 0;  // declared byteStride, 0 = tightly packed
};

Result<ViewRange> viewRange(const tinygltf::Model& gltf, int view, const std::string& where) {
  if (view < 0 || static_cast<size_t>(view) >= gltf.bufferViews.size())
    return makeError(ErrorKind::Malformed, where + " refers to bufferView " + std::to_string(view) + ", the file has " +
                     std::to_string(gltf.bufferViews.size()));
  const tinygltf::BufferView& bv = gltf.bufferViews[view];
  if (bv.buffer < 0 || static_cast<size_t>(bv.buffer) >= gltf.buffers.size())
    return makeError(ErrorKind::Malformed, where + ": bufferView " + std::to_string(view) + " refers to buffer " + std::to_string(bv.buffer) +
                     ", the file has " + std::to_string(gltf.buffers.size()));
  const std::vector<unsigned char>& buffer = gltf.buffers[bv.buffer].data;
  if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
    return makeError(ErrorKind::Malformed, where + ": bufferView " + std::to_string(view) + " (bytes " + std::to_string(bv.byteOffset) + ".." +
                     std::to_string(bv.byteOffset + bv.byteLength) + ") is out of range of buffer " +
                     std::to_string(bv.buffer) + " (" + std::to_string(buffer.size()) + " bytes)");
  return ViewRange{buffer.data() + bv.byteOffset, bv.byteLength, bv.byteStride};
}

// Checks that `count` elements of `elementSize` bytes, `stride` apart,
// starting at `offset`, fit in `available` bytes, without overflow.
bool fits(size_t offset, size_t count, size_t stride, size_t elementSize, size_t available) {
  if (count == 0) return offset <= available;
  if (offset > available) return false;
  const size_t room = available - offset;
  if (elementSize > room) return false;
  return (count - 1) <= (room - elementSize) / stride;
}

// The accessor's dense elements: where they start and how far apart, checked
// to fit in their bufferView. No bufferView: the base is all zeros (the usual
// form of a sparse morph target), data stays null.
struct DenseRange {
  const uint8_t* data = nullptr;
  size_t stride = 0;
};

Result<DenseRange> denseRange(const tinygltf::Model& gltf, const tinygltf::Accessor& acc, size_t count, size_t elementSize,
                              const std::string& where) {
  if (acc.bufferView < 0) return DenseRange{nullptr, elementSize};
  auto range = viewRange(gltf, acc.bufferView, where);
  if (!range) return range.error();
  const ViewRange base = *range;
  size_t stride = elementSize;
  if (base.stride != 0) {
    if (base.stride < elementSize)
      return makeError(ErrorKind::Malformed, where + ": byteStride " + std::to_string(base.stride) + " is smaller than the element size " +
                       std::to_string(elementSize));
    stride = base.stride;
  }
  if (!fits(acc.byteOffset, count, stride, elementSize, base.size))
    return makeError(ErrorKind::Malformed, where + ": " + std::to_string(count) + " elements of " + std::to_string(elementSize) +
                     " bytes (stride " + std::to_string(stride) + ") from byte " + std::to_string(acc.byteOffset) +
                     " run past the end of bufferView " + std::to_string(acc.bufferView) + " (" +
                     std::to_string(base.size) + " bytes)");
  return DenseRange{base.data + acc.byteOffset, stride};
}

// The accessor's sparse substitutions: their indices and values, checked to
// fit in their bufferViews (count 0 when the accessor is not sparse).
struct SparseRange {
  size_t count = 0;
  const uint8_t* indices = nullptr;
  size_t indexSize = 0;
  const uint8_t* values = nullptr;
};

Result<SparseRange> sparseRange(const tinygltf::Model& gltf, const tinygltf::Accessor& acc, size_t count, size_t elementSize,
                                const std::string& where) {
  if (!acc.sparse.isSparse) return SparseRange{};
  const size_t sparseCount = static_cast<size_t>(std::max(acc.sparse.count, 0));
  if (acc.sparse.count < 0 || sparseCount > count)
    return makeError(ErrorKind::Malformed, where + ": sparse count " + std::to_string(acc.sparse.count) + " is outside 0.." +
                     std::to_string(count));
  const int ict = acc.sparse.indices.componentType;
  const size_t sparseIndexSize = gltfComponentSize(ict);
  if (ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      ict != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    return makeError(ErrorKind::Malformed, where + ": sparse indices have componentType " + std::to_string(ict) +
                     ", expected an unsigned integer type");
  auto ir = viewRange(gltf, acc.sparse.indices.bufferView, where + " sparse indices");
  if (!ir) return ir.error();
  auto vr = viewRange(gltf, acc.sparse.values.bufferView, where + " sparse values");
  if (!vr) return vr.error();
  const ViewRange sparseIndices = *ir, sparseValues = *vr;
  if (acc.sparse.indices.byteOffset < 0 || acc.sparse.values.byteOffset < 0)
    return makeError(ErrorKind::Malformed, where + ": negative sparse byteOffset");
  if (!fits(static_cast<size_t>(acc.sparse.indices.byteOffset), sparseCount, sparseIndexSize, sparseIndexSize,
            sparseIndices.size))
    return makeError(ErrorKind::Malformed, where + ": " + std::to_string(sparseCount) + " sparse indices from byte " +
                     std::to_string(acc.sparse.indices.byteOffset) + " run past the end of bufferView " +
                     std::to_string(acc.sparse.indices.bufferView) + " (" + std::to_string(sparseIndices.size) +
                     " bytes)");
  if (!fits(static_cast<size_t>(acc.sparse.values.byteOffset), sparseCount, elementSize, elementSize,
            sparseValues.size))
    return makeError(ErrorKind::Malformed, where + ": " + std::to_string(sparseCount) + " sparse values of " + std::to_string(elementSize) +
                     " bytes from byte " + std::to_string(acc.sparse.values.byteOffset) +
                     " run past the end of bufferView " + std::to_string(acc.sparse.values.bufferView) + " (" +
                     std::to_string(sparseValues.size) + " bytes)");
  return SparseRange{sparseCount, sparseIndices.data + acc.sparse.indices.byteOffset, sparseIndexSize,
                     sparseValues.data + acc.sparse.values.byteOffset};
}

}  // namespace

int gltfComponentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;  // inverse bind matrices (float: no column padding)
    default: return 0;  // other matrices and junk are never read here
  }
}

size_t gltfComponentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_INT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

Result<size_t> GltfAccessorReader::count(int accessor, std::string_view what) const {
  if (accessor < 0 || static_cast<size_t>(accessor) >= gltf_.accessors.size())
    return makeError(ErrorKind::Malformed, prefix(accessor, what) + " does not exist; the file has " + std::to_string(gltf_.accessors.size()) +
                     " accessors");
  return gltf_.accessors[accessor].count;
}

Result<std::vector<float>> GltfAccessorReader::readFloats(int accessor, int components, std::string_view what) {
  return decode<float>(accessor, components, false, what);
}

Result<std::vector<uint32_t>> GltfAccessorReader::readIndices(int accessor, std::string_view what) {
  return decode<uint32_t>(accessor, 1, true, what);
}

template <class T>
Result<std::vector<T>> GltfAccessorReader::decode(int index, int components, bool indices, std::string_view what) {
  auto n = count(index, what);
  if (!n) return n.error();
  const tinygltf::Accessor& acc = gltf_.accessors[index];
  const std::string where = prefix(index, what);
  const int accComponents = gltfComponentCount(acc.type);
  if (accComponents != components)
    return makeError(ErrorKind::Malformed, where + " has type " + typeName(acc.type) + ", expected " +
                     (components == 1    ? std::string("SCALAR")
                      : components == 16 ? std::string("MAT4")
                                         : "VEC" + std::to_string(components)));
  const size_t compSize = gltfComponentSize(acc.componentType);
  if (compSize == 0)
    return makeError(ErrorKind::Malformed, where + " has unknown componentType " + std::to_string(acc.componentType));
  if (indices && acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    return makeError(ErrorKind::Malformed, where + " must hold unsigned integers, has componentType " + std::to_string(acc.componentType));
  const size_t elementSize = compSize * static_cast<size_t>(components);
  const size_t count = *n;

  // Nothing is allocated until the source ranges are known to hold `count` elements.
  auto dense = denseRange(gltf_, acc, count, elementSize, where);
  if (!dense) return dense.error();
  auto sparse = sparseRange(gltf_, acc, count, elementSize, where);
  if (!sparse) return sparse.error();

  const size_t valueCount = count * static_cast<size_t>(components);
  if (count > std::numeric_limits<size_t>::max() / (sizeof(T) * components))
    return makeError(ErrorKind::TooLarge, where + ": count " + std::to_string(count) + " is absurd");
  if (auto ok = budget_.charge(valueCount, sizeof(T), where); !ok) return ok.error();

  std::vector<T> out(valueCount, T{});
  auto readElement = [&](const uint8_t* src, T* dst) {
    for (int c = 0; c < components; ++c) {
      const uint8_t* p = src + static_cast<size_t>(c) * compSize;
      if constexpr (std::is_same_v<T, float>)
        dst[c] = componentAsFloat(p, acc.componentType, acc.normalized);
      else
        dst[c] = componentAsIndex(p, acc.componentType);
    }
  };
  if (dense->data)
    for (size_t i = 0; i < count; ++i) readElement(dense->data + i * dense->stride, out.data() + i * components);
  for (size_t s = 0; s < sparse->count; ++s) {
    const uint32_t target = componentAsIndex(sparse->indices + s * sparse->indexSize, acc.sparse.indices.componentType);
    if (target >= count)
      return makeError(ErrorKind::Malformed, where + ": sparse index " + std::to_string(target) + " (entry " + std::to_string(s) +
                       ") is out of range of " + std::to_string(count) + " elements");
    readElement(sparse->values + s * elementSize, out.data() + static_cast<size_t>(target) * components);
  }
  if constexpr (std::is_same_v<T, float>) {
    for (size_t i = 0; i < out.size(); ++i)
      if (!std::isfinite(out[i]))
        return makeError(ErrorKind::Malformed, where + ": element " + std::to_string(i / components) + " is " +
                         (std::isnan(out[i]) ? "NaN" : "infinite"));
  }
  return out;
}

}  // namespace eng
