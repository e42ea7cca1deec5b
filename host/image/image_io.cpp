// image_io.cpp: OpenImageIO behind the C API of image_io.h. Every exception and OIIO
// error stops at this boundary and comes back as text.
#include "image/image_io.h"
#include "image/levels8.h"
#include "image/png_writer.h"
#include "image/staged_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>

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

// The colour space OIIO records for an 8-bit file ("Gamma2.2" is OIIO's name for a power).
std::string color_space(const rc_encoding &e) {
  if (e.curve == RC_CURVE_SRGB) return "sRGB";
  if (e.curve == RC_CURVE_GAMMA) {
    char name[32];
    std::snprintf(name, sizeof name, "Gamma%g", static_cast<double>(e.gamma));
    return name;
  }
  return "Linear";
}

std::string errno_text(const std::string &what, int e) { return what + ": " + std::strerror(e); }

// Writes through a FILE* this module owns, so every failed write is seen here even where
// a format plugin ignores it: OpenImageIO 2.4's PNG and BMP writers reported success on a
// full disk and left a truncated file. A failed write is reported to the plugin as done:
// the file is discarded anyway, and libjpeg answers a short write with exit(1) from
// inside the library, where no error path of ours could run.
class checked_file : public OIIO::Filesystem::IOProxy {
 public:
  explicit checked_file(FILE *f) : IOProxy("", OIIO::Filesystem::IOProxy::Write), file_(f) {}
  // Not "file": OpenImageIO hands a file proxy's FILE* straight to libjpeg.
  const char *proxytype() const override { return "checked"; }
  bool seek(int64_t offset) override {
    if (fseeko(file_, offset, SEEK_SET) != 0) note_error();
    m_pos = offset;
    return true;
  }
  size_t write(const void *buf, size_t size) override {
    if (size && fwrite(buf, 1, size, file_) != size) note_error();
    m_pos += static_cast<int64_t>(size);
    return size;
  }
  size_t pwrite(const void *buf, size_t size, int64_t offset) override {
    int64_t at = m_pos;
    seek(offset);
    write(buf, size);
    seek(at);
    return size;
  }
  size_t size() const override {
    struct stat st;
    fflush(file_);
    return fstat(fileno(file_), &st) == 0 ? static_cast<size_t>(st.st_size) : 0;
  }
  void flush() const override { fflush(file_); }
  int error = 0;

 private:
  void note_error() {
    if (!error) error = errno ? errno : EIO;
  }
  FILE *file_;
};

}  // namespace

struct rc_image_writer {
  std::unique_ptr<ImageOutput> out;
  std::unique_ptr<checked_file> proxy;
  rc_staged staged{}; // the temporary and the target (staged_file.h)
  int width = 0, height = 0, channels = 0, next_row = 0;
  bool fp = false;
  rc_levels levels;                   // 8-bit formats: the encoding's table (levels8.h)
  std::vector<unsigned char> encoded; // one band of levels
};

namespace {

// Why a write failed: the proxy's errno when a write or seek failed (whatever the plugin
// made of it), else the plugin's own error, else `fallback`.
std::string write_error(rc_image_writer *w, const std::string &plugin_error, const char *fallback) {
  if (w->proxy && w->proxy->error) return errno_text("write failed", w->proxy->error);
  return plugin_error.empty() ? fallback : plugin_error;
}

// Gives up the temporary. A plugin closed on an unfinished image complains on stderr
// (libpng: "No IDATs written into file") after the run has already said what failed:
// stderr is pointed at /dev/null meanwhile.
void discard_temp(rc_image_writer *w) {
  if (w->out) {
    fflush(stderr);
    int saved = dup(STDERR_FILENO), null = open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (saved >= 0 && null >= 0) dup2(null, STDERR_FILENO);
    w->out.reset();
    if (saved >= 0 && null >= 0) dup2(saved, STDERR_FILENO);
    if (saved >= 0) close(saved);
    if (null >= 0) close(null);
  }
  w->proxy.reset();
  rc_staged_discard(&w->staged);
}

// Every byte on disk before the file gets its final name: the plugin's close, the
// proxy's writes, stdio's buffer, fsync.
bool finish_temp(rc_image_writer *w, std::string &err) {
  if (!w->out) return true; // finished before
  bool closed = w->out->close();
  std::string plugin_error = closed ? "" : w->out->geterror();
  w->out.reset();
  char e[512] = "";
  if (!closed || w->proxy->error) err = write_error(w, plugin_error, "the image writer failed");
  else if (rc_staged_sync(&w->staged, e, sizeof e) != 0) err = e;
  return err.empty();
}

}  // namespace

extern "C" rc_image_writer *rc_image_writer_open(const char *path, int width, int height, int channels,
                                                 const char *const *names, rc_encoding enc, bool truncate,
                                                 const rc_image_meta *meta, int meta_count, char *err,
                                                 size_t err_len) {
  try {
    auto w = std::make_unique<rc_image_writer>();
    w->out = ImageOutput::create(path);
    if (!w->out) {
      set_error(err, err_len, std::string("no image format for this file name (") + OIIO::geterror() + ")");
      return nullptr;
    }
    std::string format = w->out->format_name();
    if (!w->out->supports("ioproxy")) {
      set_error(err, err_len, "the " + format + " writer cannot report write errors; use .png, .exr, .tif, .bmp, .ppm, .hdr or .jpg");
      return nullptr;
    }
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
    spec.attribute("oiio:ColorSpace", w->fp ? std::string("Linear") : color_space(enc));
    spec.attribute("Software", "vkraycast");
    if (format == "png") {
      // png_writer.h says why these.
      spec.attribute("png:compressionLevel", RC_PNG_ZLIB_LEVEL);
      spec.attribute("png:filter", RC_PNG_FILTER_SUB);
    }
    for (int i = 0; i < meta_count; i++) spec.attribute(meta[i].name, meta[i].value);
    w->width = width, w->height = height, w->channels = channels;
    if (!w->fp) rc_levels_make(enc, truncate, &w->levels);
    if (rc_staged_open(&w->staged, path, err, err_len) != 0) return nullptr;
    w->proxy = std::make_unique<checked_file>(w->staged.file);
    w->out->set_ioproxy(w->proxy.get());
    if (!w->out->open(path, spec)) {
      set_error(err, err_len, write_error(w.get(), w->out->geterror(), "cannot start the image"));
      discard_temp(w.get());
      return nullptr;
    }
    return w.release();
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return nullptr;
  }
}

extern "C" const char *rc_image_writer_temp_path(const rc_image_writer *w) { return rc_staged_temp_path(&w->staged); }

namespace {

// Rows of `format` data (FLOAT, or UINT8 levels) after the last ones written.
int write_rows(rc_image_writer *w, int rows, TypeDesc format, const void *data, char *err, size_t err_len) {
  if (rows <= 0) return 0;
  if (w->next_row + rows > w->height) {
    set_error(err, err_len, "more rows than the image has");
    return -1;
  }
  if (!w->out->write_scanlines(w->next_row, w->next_row + rows, 0, format, data) || w->proxy->error) {
    set_error(err, err_len, write_error(w, w->out->geterror(), "the image writer failed"));
    return -1;
  }
  w->next_row += rows;
  return 0;
}

}  // namespace

extern "C" int rc_image_writer_rows(rc_image_writer *w, int rows, const float *pixels, char *err, size_t err_len) {
  try {
    if (w->fp || rows <= 0) return write_rows(w, rows, TypeDesc::FLOAT, pixels, err, err_len);
    // 8-bit: each value's level from the table, so OIIO converts nothing.
    size_t n = static_cast<size_t>(w->width) * rows * w->channels;
    w->encoded.resize(n);
    for (size_t i = 0; i < n; i++) w->encoded[i] = rc_level_of(&w->levels, pixels[i]);
    return write_rows(w, rows, TypeDesc::UINT8, w->encoded.data(), err, err_len);
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}

extern "C" int rc_image_writer_levels(rc_image_writer *w, int rows, const unsigned char *levels, char *err,
                                      size_t err_len) {
  try {
    if (w->fp) {
      set_error(err, err_len, "8-bit levels given to a float format");
      return -1;
    }
    return write_rows(w, rows, TypeDesc::UINT8, levels, err, err_len);
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}

extern "C" int rc_image_writer_finish(rc_image_writer *w, char *err, size_t err_len) {
  try {
    if (w->next_row != w->height) {
      set_error(err, err_len, "the image is incomplete");
      return -1;
    }
    std::string e;
    if (finish_temp(w, e)) return 0;
    set_error(err, err_len, e);
    return -1;
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}

extern "C" rc_image_writer *rc_file_writer_open(const char *path, const void *bytes, size_t len, char *err,
                                                size_t err_len) {
  try {
    auto w = std::make_unique<rc_image_writer>();
    if (rc_staged_open(&w->staged, path, err, err_len) != 0) return nullptr;
    if (rc_staged_write_all(&w->staged, bytes, len, err, err_len) != 0) {
      discard_temp(w.get());
      return nullptr;
    }
    return w.release(); // no rows: finish has nothing left to do, close names it
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return nullptr;
  }
}

extern "C" int rc_image_writer_close(rc_image_writer *w, int commit, char *err, size_t err_len) {
  std::unique_ptr<rc_image_writer> owned(w);
  if (!commit) {
    discard_temp(w);
    return 0;
  }
  try {
    if (rc_image_writer_finish(w, err, err_len) != 0) {
      discard_temp(w);
      return -1;
    }
    w->proxy.reset();
    return rc_staged_commit(&w->staged, err, err_len);
  } catch (const std::exception &e) {
    discard_temp(w);
    set_error(err, err_len, e.what());
    return -1;
  }
}

namespace {

int write_image(const char *path, int width, int height, int channels, const float *pixels, rc_encoding enc,
                bool truncate, char *err, size_t err_len) {
  rc_image_writer *w =
      rc_image_writer_open(path, width, height, channels, nullptr, enc, truncate, nullptr, 0, err, err_len);
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

extern "C" int rc_image_stores_levels(const char *path) {
  try {
    auto out = ImageOutput::create(path);
    return out && !is_float_format(out->format_name()) ? 1 : 0;
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

struct rc_image_reader {
  std::unique_ptr<ImageInput> in;
};

extern "C" rc_image_reader *rc_image_reader_open(const char *path, int *width, int *height, int *channels,
                                                 bool *float32, char *err, size_t err_len) {
  try {
    auto r = std::make_unique<rc_image_reader>();
    r->in = ImageInput::open(path);
    if (!r->in) {
      set_error(err, err_len, OIIO::geterror());
      return nullptr;
    }
    const ImageSpec &spec = r->in->spec();
    /* Layouts the row reader cannot take, refused by name. */
    const char *unsupported = spec.deep ? "a deep image (several samples per pixel)"
                              : spec.depth > 1 ? "a volume (depth above 1)"
                                               : nullptr;
    if (unsupported) {
      set_error(err, err_len, std::string("it is ") + unsupported + ", not a flat image");
      return nullptr;
    }
    *width = spec.width;
    *height = spec.height;
    *channels = spec.nchannels;
    *float32 = spec.format == TypeDesc::FLOAT;
    for (const TypeDesc &t : spec.channelformats) *float32 = *float32 && t == TypeDesc::FLOAT;
    return r.release();
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return nullptr;
  }
}

extern "C" int rc_image_reader_meta(const rc_image_reader *r, const char *name, char *value, size_t len) {
  const OIIO::ParamValue *p = r->in->spec().find_attribute(name, TypeDesc::STRING);
  if (!p) return 0;
  std::snprintf(value, len, "%s", p->get_string().c_str());
  return 1;
}

extern "C" int rc_image_reader_channel(const rc_image_reader *r, int c, char *name, size_t len) {
  const ImageSpec &spec = r->in->spec();
  if (c < 0 || c >= spec.nchannels) return 0;
  std::snprintf(name, len, "%s", spec.channel_name(c).c_str());
  return 1;
}

/* Rows [y0, y1) counted from the top of the data window, wherever the file puts it. A
 * tiled file is read by whole tiles: OpenImageIO 2.4's scanline emulation over tiles died
 * of SIGFPE on a tiled OpenEXR part. */
extern "C" int rc_image_reader_rows(rc_image_reader *r, int y0, int y1, float *pixels, char *err, size_t err_len) {
  try {
    const ImageSpec &spec = r->in->spec();
    const int nch = spec.nchannels;
    bool ok;
    if (spec.tile_width > 0 && spec.tile_height > 0) {
      const int th = spec.tile_height;
      const int ta = y0 / th * th, tb = std::min(spec.height, (y1 + th - 1) / th * th);
      std::vector<float> tiles((size_t)(tb - ta) * (size_t)spec.width * (size_t)nch);
      ok = r->in->read_tiles(0, 0, spec.x, spec.x + spec.width, spec.y + ta, spec.y + tb, spec.z,
                             spec.z + std::max(1, spec.depth), 0, nch, TypeDesc::FLOAT, tiles.data());
      if (ok)
        std::memcpy(pixels, tiles.data() + (size_t)(y0 - ta) * (size_t)spec.width * (size_t)nch,
                    (size_t)(y1 - y0) * (size_t)spec.width * (size_t)nch * sizeof(float));
    } else {
      ok = r->in->read_scanlines(0, 0, spec.y + y0, spec.y + y1, spec.z, 0, nch, TypeDesc::FLOAT, pixels);
    }
    if (ok) return 0;
    set_error(err, err_len, r->in->geterror());
    return -1;
  } catch (const std::exception &e) {
    set_error(err, err_len, e.what());
    return -1;
  }
}

extern "C" void rc_image_reader_close(rc_image_reader *r) {
  if (r && r->in) r->in->close();
  delete r;
}
