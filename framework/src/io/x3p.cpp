#include "io/x3p.hpp"

#include <md5.h>
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <pugixml.hpp>
#include <sstream>

#include "interrupt.hpp"
#include "io/atomic_file.hpp"
#include "io/read_file.hpp"
#include "topomill/error.hpp"
#include "topomill/version.hpp"

namespace topomill {

namespace {

// Bytes hashed or converted between two checks of the stop flag (a 730 MB map takes seconds).
constexpr std::size_t kStopCheckBytes = std::size_t{1} << 24;

std::string md5_hex(const void* data, std::size_t size) {
  MD5_CTX ctx;
  MD5Init(&ctx);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  for (std::size_t at = 0; at < size; at += kStopCheckBytes) {
    throw_if_interrupted();
    MD5Update(&ctx, bytes + at, std::min(kStopCheckBytes, size - at));
  }
  char out[MD5_DIGEST_STRING_LENGTH];
  MD5End(&ctx, out);
  return out;
}

// libzip asks this while it compresses: a stop request cancels the archive.
int cancel_on_stop(zip_t*, void*) {
  return stop_flag().load() ? 1 : 0;
}

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};

class Archive {
 public:
  explicit Archive(const std::string& path) : path_(path) {
    regular_file_size(path, readable_bytes(), "an x3p file (a zip archive)");
    int err = 0;
    zip_.reset(zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &err));
    if (!zip_) {
      zip_error_t ze;
      zip_error_init_with_code(&ze, err);
      std::string why = zip_error_strerror(&ze);
      zip_error_fini(&ze);
      fail("not a readable x3p (zip) file: " + why);
    }
  }
  bool has(const std::string& name) const {
    return zip_name_locate(zip_.get(), name.c_str(), 0) >= 0;
  }
  // The entry `name`, whose size must be at most `max_bytes` (exactly, when `exact`). The size
  // the zip header claims is checked before anything is allocated: against that bound, and
  // against what its compressed bytes can hold (deflate expands 1032-fold at most; a 4 KB file
  // claiming a 4 GiB entry cost 4.2 GB and 15 s before).
  std::string read(const std::string& name, std::uint64_t max_bytes, bool exact = false) const {
    zip_stat_t st;
    if (zip_stat(zip_.get(), name.c_str(), 0, &st) != 0) fail("the archive has no '" + name + "'");
    if (!(st.valid & ZIP_STAT_SIZE) || !(st.valid & ZIP_STAT_COMP_SIZE))
      fail("the archive does not give the size of '" + name + "'");
    if (exact ? st.size != max_bytes : st.size > max_bytes)
      fail("'" + name + "' holds " + std::to_string(st.size) + " bytes: expected " +
           (exact ? "" : "at most ") + std::to_string(max_bytes));
    if (static_cast<double>(st.size) > 1100.0 * static_cast<double>(st.comp_size) + 1024)
      fail("'" + name + "' claims " + std::to_string(st.size) + " bytes from " +
           std::to_string(st.comp_size) + " compressed: more than compression can produce");
    std::unique_ptr<zip_file_t, int (*)(zip_file_t*)> f(zip_fopen(zip_.get(), name.c_str(), 0),
                                                        zip_fclose);
    if (!f) fail("cannot open '" + name + "' in the archive");
    std::string data(st.size, '\0');
    if (zip_fread(f.get(), data.data(), st.size) != static_cast<zip_int64_t>(st.size))
      fail("'" + name + "' is truncated or corrupt");
    return data;
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(SourceRef{path_}, "", why);
  }

 private:
  std::string path_;
  std::unique_ptr<zip_t, ZipCloser> zip_;
};

// Text for an XML element: the five markup characters escaped.
std::string xml_text(const std::string& text) {
  std::string out;
  for (const char c : text) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  return out;
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The points of a DataLink: binary little-endian values of the CZ DataType (exactly nx x ny of
// them) and, where linked, the valid points' bits, each checked against its MD5 where given.
void read_linked_points(Archive& zip, const pugi::xml_node& link, const std::string& type,
                        double z_off, double z_inc, Surface& s) {
  const std::size_t n = s.map.grid.size();
  const std::string name = link.child("PointDataLink").text().as_string();
  const std::size_t width = type == "I" ? 2 : type == "L" || type == "F" ? 4 : type == "D" ? 8 : 0;
  if (!width) zip.fail("unknown CZ DataType '" + type + "' (expected I, L, F or D)");
  // Exactly what the matrix dimension asks for (nx x ny points of type CZ DataType).
  const std::string data = zip.read(name, n * width, /*exact=*/true);
  const std::string want = link.child("MD5ChecksumPointData").text().as_string();
  if (!want.empty() && lower(want) != md5_hex(data.data(), data.size()))
    zip.fail("the MD5 checksum of " + name + " does not match MD5ChecksumPointData");
  for (std::size_t i = 0; i < n; ++i) {
    const char* p = data.data() + i * width;  // little-endian, as the standard says
    double v = 0;
    if (type == "I") {
      std::int16_t x;
      std::memcpy(&x, p, 2);
      v = x;
    }
    if (type == "L") {
      std::int32_t x;
      std::memcpy(&x, p, 4);
      v = x;
    }
    if (type == "F") {
      float x;
      std::memcpy(&x, p, 4);
      v = x;
    }
    if (type == "D") std::memcpy(&v, p, 8);
    s.map.z[i] = (z_off + z_inc * v) * 1e3;
  }
  const std::string valid_name = link.child("ValidPointsLink").text().as_string();
  if (!valid_name.empty()) {
    const std::string bits = zip.read(valid_name, (n + 7) / 8 + 64);
    const std::string vwant = link.child("MD5ChecksumValidPoints").text().as_string();
    if (!vwant.empty() && lower(vwant) != md5_hex(bits.data(), bits.size()))
      zip.fail("the MD5 checksum of " + valid_name + " does not match MD5ChecksumValidPoints");
    if (bits.size() < (n + 7) / 8)
      zip.fail(valid_name + " holds " + std::to_string(bits.size()) + " bytes; " +
               std::to_string(n) + " points need " + std::to_string((n + 7) / 8));
    for (std::size_t i = 0; i < n; ++i)
      s.valid[i] = (static_cast<unsigned char>(bits[i / 8]) >> (i % 8)) & 1u;
  }
}

// The points of a DataList, one Datum each (an empty Datum an invalid point).
void read_listed_points(Archive& zip, const pugi::xml_node& list, double z_off, double z_inc,
                        Surface& s) {
  const std::size_t n = s.map.grid.size();
  std::size_t i = 0;
  for (pugi::xml_node d = list.child("Datum"); d; d = d.next_sibling("Datum"), ++i) {
    if (i >= n) zip.fail("DataList holds more points than the matrix dimension");
    const std::string text = d.text().as_string();
    if (text.empty()) {
      s.valid[i] = 0;  // an empty Datum is an invalid point
      s.map.z[i] = 0;
    } else {
      s.map.z[i] = (z_off + z_inc * d.text().as_double()) * 1e3;
    }
  }
  if (i != n)
    zip.fail("DataList holds " + std::to_string(i) + " points; the matrix has " +
             std::to_string(n));
}

}  // namespace

Surface read_x3p(const std::string& path) {
  Archive zip(path);
  // main.xml: the metadata, and the heights themselves when they are a DataList (a few dozen
  // bytes a point): bounded by memory like the file.
  const std::string xml = zip.read("main.xml", readable_bytes());
  if (zip.has("md5checksum.hex")) {
    std::istringstream line(zip.read("md5checksum.hex", 4096));
    std::string want;
    line >> want;
    if (lower(want) != md5_hex(xml.data(), xml.size()))
      zip.fail("the MD5 checksum of main.xml does not match md5checksum.hex");
  }
  pugi::xml_document doc;
  if (!doc.load_buffer(xml.data(), xml.size())) zip.fail("main.xml is not well-formed XML");
  const pugi::xml_node root = doc.first_element_by_path("p:ISO5436_2");
  if (!root) zip.fail("main.xml has no p:ISO5436_2 root element");
  const pugi::xml_node axes = root.child("Record1").child("Axes");
  const pugi::xml_node dim = root.child("Record3").child("MatrixDimension");
  if (!axes || !dim) zip.fail("main.xml lacks Record1/Axes or Record3/MatrixDimension");
  const long nx = dim.child("SizeX").text().as_llong(-1),
             ny = dim.child("SizeY").text().as_llong(-1);
  const long nz = dim.child("SizeZ").text().as_llong(1);
  if (nx < 1 || ny < 1 || nz != 1 || nx > 100000 || ny > 100000 || nx * ny > 400000000L)
    zip.fail("unsupported matrix dimension " + std::to_string(nx) + " x " + std::to_string(ny) +
             " x " + std::to_string(nz) + " (one layer, up to 4e8 points)");
  auto increment = [&](const char* axis) {
    const double v = axes.child(axis).child("Increment").text().as_double(0);
    if (!(v > 0) || !std::isfinite(v))
      zip.fail(std::string("axis ") + axis + " has no positive Increment");
    return v;
  };
  const pugi::xml_node cz = axes.child("CZ");
  const std::string type = cz.child("DataType").text().as_string("D");
  const bool scaled =
      cz.child("AxisType").text().as_string("A") == std::string("I") || type == "I" || type == "L";
  const double z_inc = scaled ? cz.child("Increment").text().as_double(1.0) : 1.0;
  const double z_off = scaled ? cz.child("Offset").text().as_double(0.0) : 0.0;

  Surface s;
  s.source = path;
  Grid g;
  g.nx = static_cast<std::size_t>(nx), g.ny = static_cast<std::size_t>(ny);
  g.dx = increment("CX") * 1e3, g.dy = increment("CY") * 1e3;
  // The axes' offsets place the first point (optional; a bad one is refused, not guessed).
  auto offset = [&](const char* axis) {
    const double v = axes.child(axis).child("Offset").text().as_double(0);
    if (!std::isfinite(v) || std::abs(v) > 1e3)
      zip.fail(std::string("axis ") + axis + " has an Offset that is not a finite length");
    return v * 1e3;
  };
  g.x0 = offset("CX"), g.y0 = offset("CY");
  check_map_memory(path, static_cast<double>(nx) * static_cast<double>(ny));
  s.map = HeightMap(g);
  const std::size_t n = g.size();
  s.valid.assign(n, 1);

  const pugi::xml_node link = root.child("Record3").child("DataLink");
  const pugi::xml_node list = root.child("Record3").child("DataList");
  if (link)
    read_linked_points(zip, link, type, z_off, z_inc, s);
  else if (list)
    read_listed_points(zip, list, z_off, z_inc, s);
  else
    zip.fail("Record3 has neither a DataLink nor a DataList");
  for (std::size_t i = 0; i < n; ++i)
    if (s.valid[i] && !std::isfinite(s.map.z[i]))
      zip.fail("point " + std::to_string(i) + " is not finite (NaN or Inf) yet marked valid");
  return s;
}

void write_x3p(const std::string& path, const HeightMap& map, const FileInfo& info,
               const std::vector<std::uint8_t>& valid) {
  const Grid& g = map.grid;
  const bool masked = !valid.empty();
  std::string data(g.size() * 8, '\0'), bits;
  if (masked) bits.assign((g.size() + 7) / 8, '\0');
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (i % (kStopCheckBytes / 8) == 0) throw_if_interrupted();
    const bool ok = !masked || valid[i] != 0;
    const double v = ok ? map.z[i] * 1e-3 : 0.0;
    std::memcpy(data.data() + i * 8, &v, 8);
    if (masked && ok) bits[i / 8] = static_cast<char>(bits[i / 8] | (1u << (i % 8)));
  }
  std::string valid_link;
  if (masked)
    valid_link = "<ValidPointsLink>bindata/valid.bin</ValidPointsLink><MD5ChecksumValidPoints>" +
                 md5_hex(bits.data(), bits.size()) + "</MD5ChecksumValidPoints>";
  // A simulation has no calibration: its date is the run's, as for the measurement's Date.
  const std::string date = iso8601_utc(created_time(info));
  std::string comment = info.title.empty() ? "simulated surface" : info.title;
  if (!info.description.empty()) comment += ": " + info.description;
  std::ostringstream xml;
  xml.precision(17);
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<p:ISO5436_2 xmlns:p=\"http://www.opengps.eu/2008/ISO5436_2\">\n"
      << "<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>\n"
      << "<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>" << g.dx * 1e-3
      << "</Increment><Offset>" << g.x0 * 1e-3 << "</Offset></CX>\n"
      << "<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>" << g.dy * 1e-3
      << "</Increment><Offset>" << g.y0 * 1e-3 << "</Offset></CY>\n"
      << "<CZ><AxisType>A</AxisType><DataType>D</DataType></CZ></Axes></Record1>\n"
      << "<Record2><Date>" << date << "</Date><Creator>" << xml_text(file_creator())
      << "</Creator><Instrument><Manufacturer>topomill</Manufacturer>"
      << "<Model>simulation</Model><Serial>-</Serial><Version>" << kVersion
      << "</Version></Instrument><CalibrationDate>" << date << "</CalibrationDate>"
      << "<ProbingSystem><Type>Software</Type><Identification>topomill</Identification>"
      << "</ProbingSystem><Comment>" << xml_text(comment) << "</Comment></Record2>\n"
      << "<Record3><MatrixDimension><SizeX>" << g.nx << "</SizeX><SizeY>" << g.ny
      << "</SizeY><SizeZ>1</SizeZ></MatrixDimension><DataLink><PointDataLink>bindata/data.bin"
      << "</PointDataLink><MD5ChecksumPointData>" << md5_hex(data.data(), data.size())
      << "</MD5ChecksumPointData>" << valid_link << "</DataLink></Record3>\n"
      << "<Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>\n</p:ISO5436_2>\n";
  const std::string main_xml = xml.str();
  const std::string checksum = md5_hex(main_xml.data(), main_xml.size()) + " *main.xml\n";

  write_atomically_to(path, [&](const std::string& tmp) {
    int err = 0;
    zip_t* z = zip_open(tmp.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &err);
    if (!z) throw std::runtime_error("cannot create '" + path + "'");
    zip_register_cancel_callback_with_state(z, cancel_on_stop, nullptr, nullptr);
    auto add = [&](const char* name, const std::string& content) {
      zip_source_t* src = zip_source_buffer(z, content.data(), content.size(), 0);
      if (!src || zip_file_add(z, name, src, ZIP_FL_OVERWRITE) < 0) {
        if (src) zip_source_free(src);
        zip_discard(z);
        throw std::runtime_error("cannot write '" + std::string(name) + "' into '" + path + "'");
      }
    };
    add("main.xml", main_xml);
    add("bindata/data.bin", data);
    if (masked) add("bindata/valid.bin", bits);
    add("md5checksum.hex", checksum);
    if (zip_close(z) != 0) {
      zip_discard(z);
      throw_if_interrupted();
      throw std::runtime_error("cannot write '" + path + "'");
    }
  });
}

}  // namespace topomill
