// image_io.cpp: OpenImageIO behind the C API of image_io.h. Every exception and OIIO
// error stops at this boundary and comes back as text.
#include "image/image_io.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
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

namespace {

int write_image(const char *path, int width, int height, int channels, const char *const *names, const float *pixels,
                rc_encoding enc, bool truncate, char *err, size_t err_len) {
  try {
    auto out = ImageOutput::create(path);
    if (!out) {
      set_error(err, err_len, std::string("no image format for this file name (") + OIIO::geterror() + ")");
      return -1;
    }
    std::string format = out->format_name();
    bool fp = is_float_format(format);
    if (names && !fp) {
      set_error(err, err_len, "named channels need a float format such as .exr");
      return -1;
    }
    ImageSpec spec(width, height, channels, fp ? TypeDesc::FLOAT : TypeDesc::UINT8);
    if (names) {
      spec.channelnames.clear();
      for (int i = 0; i < channels; i++) spec.channelnames.emplace_back(names[i]);
    }
    spec.attribute("oiio:ColorSpace", fp || enc == RC_ENCODING_LINEAR ? "Linear" : "sRGB");
    spec.attribute("Software", "vkraycast");
    std::vector<float> encoded;
    const float *data = pixels;
    if (!fp) {
      // 8-bit: clamp to [0, 1] here, so OIIO's quantisation is the only rounding.
      size_t n = static_cast<size_t>(width) * height * channels;
      encoded.resize(n);
      for (size_t i = 0; i < n; i++) {
        float x = pixels[i];
        float e = enc == RC_ENCODING_SRGB ? srgb_encode(x) : (x > 1.0f ? 1.0f : (x > 0.0f ? x : 0.0f));
        // OIIO rounds x * 255; a value already on a level stays there.
        encoded[i] = truncate ? std::floor(e * 255.0f) / 255.0f : e;
      }
      data = encoded.data();
    }
    std::string tmp = temp_name(path);
    if (!out->open(tmp, spec)) {
      set_error(err, err_len, out->geterror());
      std::remove(tmp.c_str());
      return -1;
    }
    bool ok = out->write_image(TypeDesc::FLOAT, data);
    std::string msg = ok ? "" : out->geterror();
    ok = out->close() && ok;
    if (ok && std::rename(tmp.c_str(), path) != 0) {
      msg = std::string("cannot rename the finished image into place: ") + std::strerror(errno);
      ok = false;
    }
    if (!ok) {
      if (msg.empty()) msg = out->geterror();
      std::remove(tmp.c_str());
      set_error(err, err_len, msg);
      return -1;
    }
    return 0;
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}

}  // namespace

extern "C" int rc_image_write(const char *path, int width, int height, int channels, const float *pixels,
                              rc_encoding enc, bool truncate, char *err, size_t err_len) {
  return write_image(path, width, height, channels, nullptr, pixels, enc, truncate, err, err_len);
}

extern "C" int rc_image_write_named(const char *path, int width, int height, int channels, const char *const *names,
                                    const float *pixels, char *err, size_t err_len) {
  return write_image(path, width, height, channels, names, pixels, RC_ENCODING_LINEAR, false, err, err_len);
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
