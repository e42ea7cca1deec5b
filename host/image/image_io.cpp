// image_io.cpp: OpenImageIO behind the C API of image_io.h. Every exception and OIIO
// error stops at this boundary and comes back as text.
#include "image/image_io.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

void set_error(char *err, size_t len, const std::string &msg) {
  if (err && len) std::snprintf(err, len, "%s", msg.c_str());
}

bool is_float_format(const std::string &format) {
  return format == "openexr" || format == "hdr" || format == "tiff" || format == "fits";
}

float srgb_encode(float x) {
  if (!(x > 0.0f)) return 0.0f;
  if (x >= 1.0f) return 1.0f;
  return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

std::string temp_name(const std::string &path) {
  size_t slash = path.find_last_of('/');
  std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  return dir + "." + base + ".tmp" + std::to_string(static_cast<long>(getpid()));
}

}  // namespace

struct rc_image_writer {
  std::unique_ptr<ImageOutput> out;
  std::string path, tmp;
  int width = 0, height = 0, channels = 0, next_row = 0;
  bool fp = false, truncate = false;
  rc_encoding enc = RC_ENCODING_LINEAR;
  std::vector<float> encoded;
};

extern "C" rc_image_writer *rc_image_writer_open(const char *path, int width, int height, int channels,
                                                 const char *const *names, rc_encoding enc, bool truncate, char *err,
                                                 size_t err_len) {
  try {
    auto w = std::make_unique<rc_image_writer>();
    w->out = ImageOutput::create(path);
    if (!w->out) {
      set_error(err, err_len, std::string("no image format for this file name (") + OIIO::geterror() + ")");
      return nullptr;
    }
    std::string format = w->out->format_name();
    w->fp = is_float_format(format);
    if (names && !w->fp) {
      set_error(err, err_len, "named channels need a float format such as .exr");
      return nullptr;
    }
    ImageSpec spec(width, height, channels, w->fp ? TypeDesc::FLOAT : TypeDesc::UINT8);
    if (names) {
      spec.channelnames.clear();
      for (int i = 0; i < channels; i++) spec.channelnames.emplace_back(names[i]);
    }
    spec.attribute("oiio:ColorSpace", w->fp || enc == RC_ENCODING_LINEAR ? "Linear" : "sRGB");
    spec.attribute("Software", "vkraycast");
    w->path = path;
    w->tmp = temp_name(path);
    w->width = width, w->height = height, w->channels = channels;
    w->enc = enc, w->truncate = truncate;
    if (!w->out->open(w->tmp, spec)) {
      set_error(err, err_len, w->out->geterror());
      std::remove(w->tmp.c_str());
      return nullptr;
    }
    return w.release();
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return nullptr;
  }
}

extern "C" const char *rc_image_writer_temp_path(const rc_image_writer *w) { return w->tmp.c_str(); }

extern "C" int rc_image_writer_rows(rc_image_writer *w, int rows, const float *pixels, char *err, size_t err_len) {
  try {
    if (rows <= 0) return 0;
    if (w->next_row + rows > w->height) {
      set_error(err, err_len, "more rows than the image has");
      return -1;
    }
    const float *data = pixels;
    if (!w->fp) {
      // 8-bit: clamp (and encode) here, so OIIO's quantisation is the only rounding.
      size_t n = static_cast<size_t>(w->width) * rows * w->channels;
      w->encoded.resize(n);
      for (size_t i = 0; i < n; i++) {
        float x = pixels[i];
        float e = w->enc == RC_ENCODING_SRGB ? srgb_encode(x) : (x > 1.0f ? 1.0f : (x > 0.0f ? x : 0.0f));
        // OIIO rounds x * 255; a value already on a level stays there.
        w->encoded[i] = w->truncate ? std::floor(e * 255.0f) / 255.0f : e;
      }
      data = w->encoded.data();
    }
    if (!w->out->write_scanlines(w->next_row, w->next_row + rows, 0, TypeDesc::FLOAT, data)) {
      set_error(err, err_len, w->out->geterror());
      return -1;
    }
    w->next_row += rows;
    return 0;
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}

extern "C" int rc_image_writer_close(rc_image_writer *w, int commit, char *err, size_t err_len) {
  std::unique_ptr<rc_image_writer> owned(w);
  try {
    bool ok = commit && w->next_row == w->height;
    if (commit && !ok) set_error(err, err_len, "the image is incomplete");
    bool closed = w->out->close();
    if (ok && !closed) {
      set_error(err, err_len, w->out->geterror());
      ok = false;
    }
    if (ok && std::rename(w->tmp.c_str(), w->path.c_str()) != 0) {
      set_error(err, err_len, std::string("cannot rename the finished image into place: ") + std::strerror(errno));
      ok = false;
    }
    if (!ok) std::remove(w->tmp.c_str());
    return (ok || !commit) ? 0 : -1;
  } catch (const std::exception &e) {
    std::remove(w->tmp.c_str());
    set_error(err, err_len, e.what());
    return -1;
  }
}

namespace {

int write_image(const char *path, int width, int height, int channels, const float *pixels, rc_encoding enc,
                bool truncate, char *err, size_t err_len) {
  rc_image_writer *w = rc_image_writer_open(path, width, height, channels, nullptr, enc, truncate, err, err_len);
  if (!w) return -1;
  if (rc_image_writer_rows(w, height, pixels, err, err_len) != 0) {
    rc_image_writer_close(w, 0, nullptr, 0);
    return -1;
  }
  return rc_image_writer_close(w, 1, err, err_len);
}

}  // namespace

extern "C" int rc_image_write(const char *path, int width, int height, int channels, const float *pixels,
                              rc_encoding enc, bool truncate, char *err, size_t err_len) {
  return write_image(path, width, height, channels, pixels, enc, truncate, err, err_len);
}

extern "C" int rc_image_can_write(const char *path) {
  try {
    return ImageOutput::create(path) ? 1 : 0;
  } catch (const std::exception &) {
    return 0;
  }
}

extern "C" int rc_image_read(const char *path, int *width, int *height, int *channels, float **pixels, char *err,
                             size_t err_len) {
  int n = 0;
  return rc_image_read_named(path, width, height, channels, pixels, nullptr, 0, &n, err, err_len);
}

extern "C" int rc_image_read_named(const char *path, int *width, int *height, int *channels, float **pixels,
                                   char (*names)[32], int max_names, int *name_count, char *err, size_t err_len) {
  *pixels = nullptr;
  *name_count = 0;
  try {
    auto in = ImageInput::open(path);
    if (!in) {
      set_error(err, err_len, OIIO::geterror());
      return -1;
    }
    const ImageSpec &spec = in->spec();
    size_t n = static_cast<size_t>(spec.width) * spec.height * spec.nchannels;
    float *buf = static_cast<float *>(std::malloc(n * sizeof(float)));
    if (!buf) {
      set_error(err, err_len, "out of memory");
      return -1;
    }
    if (!in->read_image(0, 0, 0, spec.nchannels, TypeDesc::FLOAT, buf)) {
      set_error(err, err_len, in->geterror());
      std::free(buf);
      return -1;
    }
    for (int i = 0; i < spec.nchannels && i < max_names; i++) {
      std::snprintf(names[i], 32, "%s", spec.channel_name(i).c_str());
      *name_count = i + 1;
    }
    *width = spec.width;
    *height = spec.height;
    *channels = spec.nchannels;
    *pixels = buf;
    return 0;
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}
