#pragma once
// The byte layer of io/Snapshot: a writer and a reader with the same interface, so one
// function template (`transfer` in Snapshot.cpp) describes the format once for both directions.
// Values are stored as the host's bytes (the header carries a byte-order mark). The reader checks
// every length against the bytes left before allocating, so a corrupt or hostile file gives a
// CoulombError naming the source, never a crash or a huge allocation.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/io/Snapshot.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

namespace coulomb::engine::io {

class SnapshotWriter {
 public:
  static constexpr bool kLoading = false;
  [[nodiscard]] std::uint32_t version() const { return kSnapshotVersion; }  // always the newest
  void raw(const void* data, std::size_t n) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    bytes_.insert(bytes_.end(), p, p + n);
  }
  /// A structural value the reader compares with its world (mismatch = wrong world).
  template <class T>
  void expect(T value, const char* /*what*/) {
    raw(&value, sizeof value);
  }
  /// A container length: written here; the reader checks it against the bytes left.
  std::size_t length(std::size_t n, std::size_t /*minBytesPerElement*/, const char* /*what*/) {
    const auto v = static_cast<std::uint64_t>(n);
    raw(&v, sizeof v);
    return n;
  }
  [[nodiscard]] std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

class SnapshotReader {
 public:
  static constexpr bool kLoading = true;
  SnapshotReader(std::span<const std::uint8_t> bytes, std::string source,
                 std::uint32_t version = kSnapshotVersion)
      : bytes_(bytes), source_(std::move(source)), version_(version) {}
  /// The format version of the data being read (kOldestReadableVersion .. kSnapshotVersion).
  [[nodiscard]] std::uint32_t version() const { return version_; }

  void raw(void* data, std::size_t n) {
    need(n, "a value");
    std::memcpy(data, bytes_.data() + offset_, n);
    offset_ += n;
  }
  template <class T>
  void expect(T value, const char* what) {
    T stored{};
    raw(&stored, sizeof stored);
    if (std::memcmp(&stored, &value, sizeof value) != 0)
      fail(std::string("does not match this world: ") + what + " differs (snapshot " +
           show(stored) + ", world " + show(value) +
           "); restore into a World built from the same scene");
  }
  std::size_t length(std::size_t /*current*/, std::size_t minBytesPerElement, const char* what) {
    std::uint64_t n = 0;
    raw(&n, sizeof n);
    if (minBytesPerElement > 0 && n > remaining() / minBytesPerElement)
      fail(std::string("truncated or corrupt: ") + what + " claims " + std::to_string(n) +
           " elements but only " + std::to_string(remaining()) + " bytes are left");
    return static_cast<std::size_t>(n);
  }
  void need(std::size_t n, const char* what) {
    if (n > remaining())
      fail(std::string("truncated: ") + what + " needs " + std::to_string(n) + " bytes at offset " +
           std::to_string(offset_) + ", " + std::to_string(remaining()) + " left");
  }
  [[noreturn]] void fail(const std::string& message) const {
    throw CoulombError("snapshot '" + source_ + "': " + message);
  }
  [[nodiscard]] std::size_t remaining() const { return bytes_.size() - offset_; }

 private:
  template <class T>
  static std::string show(const T& v) {
    if constexpr (std::is_arithmetic_v<T>)
      return std::to_string(v);
    else if constexpr (std::is_enum_v<T>)
      return std::to_string(static_cast<long long>(v));
    else
      return "?";
  }
  std::span<const std::uint8_t> bytes_;
  std::size_t offset_ = 0;
  std::string source_;
  std::uint32_t version_;
};

// ---- values, the same call for both directions -------------------------------------------------

template <class Ar, class T>
requires(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) void io(Ar& ar, T& v) {
  ar.raw(&v, sizeof v);
}

template <class Ar>
void io(Ar& ar, bool& v) {  // one byte, 0 or 1 (any other byte would be UB as a bool)
  std::uint8_t byte = v ? 1 : 0;
  ar.raw(&byte, 1);
  if constexpr (Ar::kLoading)
    if (byte > 1) ar.fail("corrupt: a flag holds " + std::to_string(byte));
  v = byte != 0;
}

/// An enum stored as its underlying integer, checked to be <= maxValue on reading.
template <class Ar, class E>
requires std::is_enum_v<E>
void ioEnum(Ar& ar, E& v, E maxValue) {
  auto raw = static_cast<long long>(v);  // 8 bytes whatever the underlying type
  ar.raw(&raw, sizeof raw);
  if constexpr (Ar::kLoading)
    if (raw < 0 || raw > static_cast<long long>(maxValue))
      ar.fail("corrupt: an enumeration holds " + std::to_string(raw));
  v = static_cast<E>(raw);
}

template <class Ar>
void io(Ar& ar, std::string& s) {
  const std::size_t n = ar.length(s.size(), 1, "a string");
  if constexpr (Ar::kLoading) s.resize(n);
  ar.raw(s.data(), n);
}

template <class Ar, class Tag>
void io(Ar& ar, geometry::TypedId<Tag>& id) {
  io(ar, id.index);
  io(ar, id.generation);
}

/// Any Eigen matrix of doubles, fixed or dynamic: rows, cols, then the coefficients.
template <class Ar, class Derived>
void io(Ar& ar, Eigen::PlainObjectBase<Derived>& m) {
  static_assert(std::is_same_v<typename Derived::Scalar, double>);
  std::uint32_t rows = static_cast<std::uint32_t>(m.rows()),
                cols = static_cast<std::uint32_t>(m.cols());
  io(ar, rows);
  io(ar, cols);
  if constexpr (Ar::kLoading) {
    const auto fits = [](std::uint32_t n, int fixed, int max) {
      return (fixed == Eigen::Dynamic || n == static_cast<std::uint32_t>(fixed)) &&
             (max == Eigen::Dynamic || n <= static_cast<std::uint32_t>(max));
    };
    if (!fits(rows, Derived::RowsAtCompileTime, Derived::MaxRowsAtCompileTime) ||
        !fits(cols, Derived::ColsAtCompileTime, Derived::MaxColsAtCompileTime))
      ar.fail("corrupt: a matrix has the wrong shape " + std::to_string(rows) + " x " +
              std::to_string(cols));
    ar.need(std::size_t{rows} * cols * sizeof(double), "a matrix");
    m.resize(rows, cols);
  }
  ar.raw(m.data(), sizeof(double) * m.size());
}

template <class Ar>
void io(Ar& ar, Eigen::Quaterniond& q) {
  io(ar, q.coeffs());
}

template <class Ar>
void io(Ar& ar, geometry::Pose& pose) {
  io(ar, pose.rotation);
  io(ar, pose.position);
}

template <class Ar, class T>
void io(Ar& ar, std::vector<T>& v) {
  const std::size_t n = ar.length(v.size(), 1, "a list");
  if constexpr (Ar::kLoading) v.resize(n);
  for (T& x : v) io(ar, x);
}

}  // namespace coulomb::engine::io
