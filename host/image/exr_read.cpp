/* exr_read.cpp: the readers of image_io.h for OpenEXR files, through OpenEXR alone, built
 * with exr_write.cpp as vkraycast-exr.so. Loading OpenImageIO's ~260 libraries costs about 0.2 s of CPU
 * (image_load.c); OpenEXR's ten cost about 2 ms, and `compare` of two EXRs needs nothing
 * else (docs/performance.md, "Process start-up", finding 13). image_load.c tries this
 * module first for a name ending in .exr and falls back to OpenImageIO's reader whenever
 * this one cannot read the file (a deep or subsampled image, a damaged one: its messages
 * stay OpenImageIO's). What it hands out is what OpenImageIO's reader hands out for the
 * same file: the data window's pixels as float, rows top to bottom, the channels in
 * OpenImageIO's order, and the header's string attributes by name, plus "compression" by
 * OpenImageIO's names of the methods; ctest `exr_reader` compares the two. */
#include "image/exr_module.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfCompression.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStringAttribute.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <vector>

namespace {

/* OpenImageIO's order of an EXR's channels (its OpenEXR reader sorts them so): by layer,
 * the name before the last '.', the unlayered first; within a layer R, G, B, A in that
 * order, then the rest in the file's order, which OpenEXR keeps sorted by name. */
int colour_rank(const std::string &name) {
  size_t dot = name.rfind('.');
  std::string suffix = dot == std::string::npos ? name : name.substr(dot + 1);
  static const char *const rgba[] = {"R", "G", "B", "A"};
  for (int i = 0; i < 4; i++)
    if (suffix == rgba[i]) return i;
  return 4;
}

std::string layer_of(const std::string &name) {
  size_t dot = name.rfind('.');
  return dot == std::string::npos ? std::string() : name.substr(0, dot + 1);
}

}  // namespace

struct rc_image_reader {
  std::unique_ptr<Imf::InputFile> in;
  Imath::Box2i window;
  std::vector<std::string> names; /* OpenImageIO's order */
  bool float32 = true;
};

/* Opens `path` and checks that every channel is one sample a pixel (subsampled channels
 * are left to OpenImageIO). Throws on any failure. */
static std::unique_ptr<rc_image_reader> open_exr(const char *path) {
  auto r = std::make_unique<rc_image_reader>();
  rc_exr_threads();
  r->in = std::make_unique<Imf::InputFile>(path);
  const Imf::Header &h = r->in->header();
  r->window = h.dataWindow();
  std::vector<std::string> names;
  for (Imf::ChannelList::ConstIterator c = h.channels().begin(); c != h.channels().end(); ++c) {
    if (c.channel().xSampling != 1 || c.channel().ySampling != 1) throw std::runtime_error("subsampled channel");
    r->float32 = r->float32 && c.channel().type == Imf::FLOAT;
    names.emplace_back(c.name());
  }
  if (names.empty()) throw std::runtime_error("no channels");
  std::stable_sort(names.begin(), names.end(), [](const std::string &a, const std::string &b) {
    std::string la = layer_of(a), lb = layer_of(b);
    if (la != lb) return la < lb;
    return colour_rank(a) < colour_rank(b);
  });
  r->names = names;
  return r;
}

static int width_of(const rc_image_reader *r) { return r->window.max.x - r->window.min.x + 1; }
static int height_of(const rc_image_reader *r) { return r->window.max.y - r->window.min.y + 1; }

static void describe(const rc_image_reader *r, int *width, int *height, int *channels) {
  *width = width_of(r);
  *height = height_of(r);
  *channels = (int)r->names.size();
}

/* Rows [y0, y1) of the data window, interleaved in `names` order, as float. */
static void read_rows(rc_image_reader *r, int y0, int y1, float *pixels) {
  const size_t nch = r->names.size(), w = (size_t)width_of(r);
  Imf::FrameBuffer fb;
  const Imath::V2i origin(r->window.min.x, r->window.min.y + y0);
  for (size_t c = 0; c < nch; c++)
    fb.insert(r->names[c], Imf::Slice::Make(Imf::FLOAT, pixels + c, origin, (int64_t)w, (int64_t)(y1 - y0),
                                            nch * sizeof(float), w * nch * sizeof(float)));
  r->in->setFrameBuffer(fb);
  r->in->readPixels(r->window.min.y + y0, r->window.min.y + y1 - 1);
}

static rc_image_reader *reader_open(const char *path, int *width, int *height, int *channels, bool *float32,
                                    char *err, size_t err_len) {
  try {
    auto r = open_exr(path);
    describe(r.get(), width, height, channels);
    *float32 = r->float32;
    return r.release();
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return nullptr;
  }
}

static const char *compression_name(Imf::Compression c) {
  switch (c) {
    case Imf::NO_COMPRESSION: return "none";
    case Imf::RLE_COMPRESSION: return "rle";
    case Imf::ZIPS_COMPRESSION: return "zips";
    case Imf::ZIP_COMPRESSION: return "zip";
    case Imf::PIZ_COMPRESSION: return "piz";
    case Imf::PXR24_COMPRESSION: return "pxr24";
    case Imf::B44_COMPRESSION: return "b44";
    case Imf::B44A_COMPRESSION: return "b44a";
    case Imf::DWAA_COMPRESSION: return "dwaa";
    case Imf::DWAB_COMPRESSION: return "dwab";
    default: return "unknown";
  }
}

static int reader_meta(const rc_image_reader *r, const char *name, char *value, size_t len) {
  const Imf::Header &h = r->in->header();
  if (std::strcmp(name, "compression") == 0) {
    std::snprintf(value, len, "%s", compression_name(h.compression()));
    return 1;
  }
  const Imf::StringAttribute *a = h.findTypedAttribute<Imf::StringAttribute>(name);
  if (!a) return 0;
  std::snprintf(value, len, "%s", a->value().c_str());
  return 1;
}

static int reader_channel(const rc_image_reader *r, int c, char *name, size_t len) {
  if (c < 0 || c >= (int)r->names.size()) return 0;
  std::snprintf(name, len, "%s", r->names[(size_t)c].c_str());
  return 1;
}

static int reader_rows(rc_image_reader *r, int y0, int y1, float *pixels, char *err, size_t err_len) {
  try {
    read_rows(r, y0, y1, pixels);
    return 0;
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}

static void reader_close(rc_image_reader *r) { delete r; }

static int read_named(const char *path, int *width, int *height, int *channels, float **pixels, char (*names)[32],
                      int max_names, int *name_count, char *err, size_t err_len) {
  *pixels = nullptr;
  *name_count = 0;
  try {
    auto r = open_exr(path);
    const size_t n = (size_t)width_of(r.get()) * (size_t)height_of(r.get()) * r->names.size();
    float *buf = static_cast<float *>(std::malloc(n * sizeof(float)));
    if (!buf) {
      set_error(err, err_len, "out of memory");
      return -1;
    }
    try {
      read_rows(r.get(), 0, height_of(r.get()), buf);
    } catch (...) {
      std::free(buf);
      throw;
    }
    for (int i = 0; i < (int)r->names.size() && i < max_names; i++) {
      std::snprintf(names[i], 32, "%s", r->names[(size_t)i].c_str());
      *name_count = i + 1;
    }
    describe(r.get(), width, height, channels);
    *pixels = buf;
    return 0;
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}

/* The module's table: these readers and exr_write.cpp's writers. */
extern "C" __attribute__((visibility("default"))) const rc_image_api *rc_exr_module_api(void) {
  static rc_image_api table;
  table.version = RC_IMAGE_API_VERSION;
  table.read_named = read_named;
  table.reader_open = reader_open;
  table.reader_meta = reader_meta;
  table.reader_channel = reader_channel;
  table.reader_rows = reader_rows;
  table.reader_close = reader_close;
  rc_exr_writers(&table);
  return &table;
}
