// ModelSpec as text (spec.hpp: to_text, from_text): one block per element,
//   element <kind> "<name>"
//   <parameter> <type> <values...>
//   end
// with the types r (a number), v2, v3, v4, m3 (2, 3, 4 or 9 numbers), b (0 or
// 1), s (a quoted string), i (a body index), f, f2, f3 (1, 2 or 3 time
// functions as TimeFunction::text writes them), c (a collision shape: its
// body index, kind, size (3), position (3), axes (9, by columns), the number of
// its vertices and their coordinates).
#include <iomanip>
#include <sstream>

#include "lagmb/spec/spec.hpp"
#include "lagmb/types.hpp"

namespace lagmb {

namespace {

constexpr const char* kHeader = "lagmb-spec 1";

template <class Matrix>
void write_numbers(std::ostream& out, const Matrix& x) {
  for (int k = 0; k < int(x.size()); ++k) out << ' ' << x.data()[k];
}

void write_function(std::ostream& out, const TimeFunctionPtr& f, const std::string& element) {
  const std::string text = f ? f->text() : "";
  if (text.empty())
    throw ModelError("element '" + element +
                     "': a time function without a text form (a Python callable) cannot be written; give it as "
                     "one of lagmb's time functions");
  out << ' ' << text;
}

void write_value(std::ostream& out, const Value& value, const std::string& element) {
  std::visit(
      [&](const auto& x) {
        using T = std::decay_t<decltype(x)>;
        if constexpr (std::is_same_v<T, double>) {
          out << "r " << x;
        } else if constexpr (std::is_same_v<T, Vec2>) {
          out << "v2";
          write_numbers(out, x);
        } else if constexpr (std::is_same_v<T, Vec3>) {
          out << "v3";
          write_numbers(out, x);
        } else if constexpr (std::is_same_v<T, Vec4>) {
          out << "v4";
          write_numbers(out, x);
        } else if constexpr (std::is_same_v<T, Mat3>) {
          out << "m3";
          write_numbers(out, x);
        } else if constexpr (std::is_same_v<T, bool>) {
          out << "b " << (x ? 1 : 0);
        } else if constexpr (std::is_same_v<T, std::string>) {
          out << "s " << std::quoted(x);
        } else if constexpr (std::is_same_v<T, BodyIndex>) {
          out << "i " << x.index;
        } else if constexpr (std::is_same_v<T, TimeFunctionPtr>) {
          out << 'f';
          write_function(out, x, element);
        } else if constexpr (std::is_same_v<T, std::pair<TimeFunctionPtr, TimeFunctionPtr>>) {
          out << "f2";
          write_function(out, x.first, element);
          write_function(out, x.second, element);
        } else if constexpr (std::is_same_v<T, std::array<TimeFunctionPtr, 3>>) {
          out << "f3";
          for (const TimeFunctionPtr& f : x) write_function(out, f, element);
        } else if constexpr (std::is_same_v<T, CollisionShape>) {
          out << "c " << x.body << ' ' << shape_kind_name(x.kind);
          write_numbers(out, x.size);
          write_numbers(out, x.position);
          write_numbers(out, x.axes);
          out << ' ' << x.vertices.size();
          for (const Vec3& v : x.vertices) write_numbers(out, v);
        }
      },
      value);
}

/// Reads n numbers into a fixed-size vector or matrix.
template <class Matrix>
Matrix read_numbers(std::istream& in) {
  Matrix x;
  for (int k = 0; k < int(x.size()); ++k)
    if (!(in >> x.data()[k])) throw ModelError("a number is missing");
  return x;
}

Value read_value(std::istream& in) {
  std::string type;
  in >> type;
  if (type == "r") return read_numbers<Eigen::Matrix<double, 1, 1>>(in)[0];
  if (type == "v2") return read_numbers<Vec2>(in);
  if (type == "v3") return read_numbers<Vec3>(in);
  if (type == "v4") return read_numbers<Vec4>(in);
  if (type == "m3") return read_numbers<Mat3>(in);
  if (type == "b") {
    int b = -1;
    if (!(in >> b) || (b != 0 && b != 1)) throw ModelError("a flag must be 0 or 1");
    return b == 1;
  }
  if (type == "s") {
    std::string text;
    if (!(in >> std::quoted(text))) throw ModelError("a quoted text is missing");
    return text;
  }
  if (type == "i") {
    int index = 0;
    if (!(in >> index)) throw ModelError("a body index is missing");
    return BodyIndex{index};
  }
  if (type == "f") return time_function_from_text(in);
  if (type == "f2") {
    TimeFunctionPtr f = time_function_from_text(in);
    return std::make_pair(f, time_function_from_text(in));
  }
  if (type == "f3") {
    std::array<TimeFunctionPtr, 3> f;
    for (TimeFunctionPtr& g : f) g = time_function_from_text(in);
    return f;
  }
  if (type == "c") {
    CollisionShape shape;
    std::string kind;
    if (!(in >> shape.body >> kind)) throw ModelError("a shape's body and kind are missing");
    shape.kind = shape_kind(kind);
    shape.size = read_numbers<Vec3>(in);
    shape.position = read_numbers<Vec3>(in);
    shape.axes = read_numbers<Mat3>(in);
    long count = -1;
    if (!(in >> count) || count < 0 || count > 1000000) throw ModelError("a shape's vertex count is missing");
    for (long k = 0; k < count; ++k) shape.vertices.push_back(read_numbers<Vec3>(in));
    return shape;
  }
  throw ModelError("unknown value type '" + type + "'");
}

}  // namespace

std::string ModelSpec::to_text() const {
  std::ostringstream out;
  out << std::setprecision(17) << kHeader << "\ndimension " << dimension_ << '\n';
  if (gravity_) {
    out << "gravity";
    write_numbers(out, *gravity_);
    out << '\n';
  }
  for (const Element& e : elements_) {
    out << "element " << e.args.kind().name << ' ' << std::quoted(e.name) << '\n';
    for (const auto& [key, value] : e.args.values()) {
      if (std::holds_alternative<std::monostate>(value)) continue;
      out << key << ' ';
      write_value(out, value, e.name);
      out << '\n';
    }
    out << "end\n";
  }
  return out.str();
}

ModelSpec ModelSpec::from_text(const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  auto fail = [&](const std::string& why) -> ModelError {
    return ModelError("model text, line " + std::to_string(number) + ": " + why);
  };
  if (!std::getline(lines, line) || line != kHeader) throw ModelError("model text: not lagmb's (no '" + std::string(kHeader) + "' first)");
  ++number;
  ModelSpec spec;
  std::optional<Args> args;
  std::string name;
  while (std::getline(lines, line)) {
    ++number;
    std::istringstream in(line);
    std::string word;
    if (!(in >> word)) continue;
    try {
      if (args) {
        if (word == "end") {
          spec.add(name, std::move(*args));
          args.reset();
        } else {
          try {
            args->set(word, read_value(in));
          } catch (const ModelError& e) {
            throw ModelError("'" + word + "' of '" + name + "': " + e.what());
          }
        }
      } else if (word == "dimension") {
        int d = 0;
        in >> d;
        spec = ModelSpec(d);
      } else if (word == "gravity") {
        spec.set_gravity(read_numbers<Vec3>(in));
      } else if (word == "element") {
        std::string kind;
        in >> kind >> std::quoted(name);
        args.emplace(find_kind(kind));
      } else {
        throw ModelError("'" + word + "' where 'element', 'dimension' or 'gravity' was expected");
      }
      std::string rest;
      if (in >> rest) throw ModelError("unexpected '" + rest + "' at the end of the line");
    } catch (const ModelError& e) {
      throw fail(e.what());
    }
  }
  if (args) throw fail("the last element has no 'end'");
  return spec;
}

}  // namespace lagmb
