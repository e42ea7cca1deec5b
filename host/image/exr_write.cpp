/* exr_write.cpp: the writers of image_io.h for OpenEXR files, through OpenEXR alone (the
 * other half of vkraycast-exr.so, beside exr_read.cpp). Loading OpenImageIO to write a
 * render's .exr cost about 0.2 s of CPU a process, a fifth of the test suite's CPU time
 * (docs/performance.md, "Process start-up", finding 14). What it writes is what OpenImageIO
 * 2.4's writer made of the same call: 32-bit float channels under the same names (its
 * default names where none are given), zip compression, increasing Y, and the header's
 * Software, capDate and the caller's string attributes; ctest `exr_module` compares the
 * two writers' files. The file goes through the same transaction (staged_file.h), and every
 * write through a stream that notes a failed one, whatever OpenEXR does with it. Also the
 * plain file writer (rc_file_writer_open), which needs no image library at all. */
#include "image/exr_module.h"
#include "image/staged_file.h"

#include <ImathBox.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <ImfThreading.h>
#include <sched.h>
#include <ImfStringAttribute.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <strings.h>
#include <vector>

namespace {

std::string errno_text(const char *what, int e) { return std::string(what) + ": " + std::strerror(e); }

/* Writes to the temporary's FILE*, noting the first failed write or seek; OpenEXR goes on
 * (its destructor writes the line offsets and swallows what they throw) and the writer
 * reports the error after each band and at the end. */
class checked_stream : public Imf::OStream {
 public:
  checked_stream(FILE *f, const char *name) : Imf::OStream(name), file_(f) {}
  void write(const char c[], int n) override {
    if (n > 0 && std::fwrite(c, 1, (size_t)n, file_) != (size_t)n) note_error();
    pos_ += (uint64_t)(n > 0 ? n : 0);
  }
  uint64_t tellp() override { return pos_; }
  void seekp(uint64_t pos) override {
    if (fseeko(file_, (off_t)pos, SEEK_SET) != 0) note_error();
    pos_ = pos;
  }
  int error = 0;

 private:
  void note_error() {
    if (!error) error = errno ? errno : EIO;
  }
  FILE *file_;
  uint64_t pos_ = 0;
};

/* OpenImageIO's names for channels given none: Y alone, else R, G, B, A, channel4, ... */
std::string default_name(int channels, int c) {
  static const char *const rgba[] = {"R", "G", "B", "A"};
  if (channels == 1) return "Y";
  return c < 4 ? rgba[c] : "channel" + std::to_string(c);
}

/* The EXR standard's capDate, "YYYY:MM:DD hh:mm:ss" local time, as OpenImageIO writes its
 * DateTime. */
std::string cap_date() {
  std::time_t now = std::time(nullptr);
  std::tm local{};
  char text[32] = "";
  if (localtime_r(&now, &local)) std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local);
  return text;
}

bool is_exr(const char *path) {
  size_t n = std::strlen(path);
  return n >= 4 && strcasecmp(path + n - 4, ".exr") == 0;
}

}  // namespace

void rc_exr_threads(void) {
  static std::once_flag once;
  std::call_once(once, [] {
    cpu_set_t set;
    int n = sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : 1;
    if (n > 1) Imf::setGlobalThreadCount(n);
  });
}

struct rc_image_writer {
  rc_staged staged{};
  std::unique_ptr<checked_stream> stream; // both absent in a plain file's writer
  std::unique_ptr<Imf::OutputFile> out;
  std::vector<std::string> names;
  int width = 0, height = 0, next_row = 0;
};

namespace {

/* The stream's errno as the reason, else `fallback`. */
std::string failure(const rc_image_writer *w, const std::string &fallback) {
  return w->stream && w->stream->error ? errno_text("write failed", w->stream->error) : fallback;
}

void discard(rc_image_writer *w) {
  w->out.reset(); // its line offsets go to a file about to be removed
  w->stream.reset();
  rc_staged_discard(&w->staged);
}

/* Runs `step`, a call into OpenEXR: 0, or -1 with the reason if it threw or a write failed. */
template <class Step> int checked(rc_image_writer *w, Step step, char *err, size_t err_len) {
  try {
    step();
  } catch (const std::exception &e) {
    set_error(err, err_len, failure(w, e.what()));
    return -1;
  }
  if (w->stream->error) {
    set_error(err, err_len, failure(w, ""));
    return -1;
  }
  return 0;
}

rc_image_writer *writer_open(const char *path, int width, int height, int channels, const char *const *names,
                             rc_encoding, bool, const rc_image_meta *meta, int meta_count, char *err,
                             size_t err_len) {
  if (!is_exr(path)) {
    set_error(err, err_len, "the OpenEXR module writes .exr files only");
    return nullptr;
  }
  auto w = std::make_unique<rc_image_writer>();
  try {
    rc_exr_threads();
    Imf::Header header(width, height); // zip compression, increasing Y, the data window at 0,0
    for (int c = 0; c < channels; c++) {
      w->names.push_back(names ? std::string(names[c]) : default_name(channels, c));
      header.channels().insert(w->names.back(), Imf::Channel(Imf::FLOAT));
    }
    header.insert("Software", Imf::StringAttribute("vkraycast"));
    header.insert("capDate", Imf::StringAttribute(cap_date()));
    for (int i = 0; i < meta_count; i++) header.insert(meta[i].name, Imf::StringAttribute(meta[i].value));
    w->width = width, w->height = height;
    if (rc_staged_open(&w->staged, path, err, err_len) != 0) return nullptr;
    w->stream = std::make_unique<checked_stream>(w->staged.file, path);
    // The header is written here.
    if (checked(w.get(), [&] { w->out = std::make_unique<Imf::OutputFile>(*w->stream, header); }, err, err_len) != 0) {
      discard(w.get());
      return nullptr;
    }
    return w.release();
  } catch (const std::exception &e) {
    set_error(err, err_len, failure(w.get(), e.what()));
    discard(w.get());
    return nullptr;
  }
}

int writer_rows(rc_image_writer *w, int rows, const float *pixels, char *err, size_t err_len) {
  if (rows <= 0) return 0;
  if (w->next_row + rows > w->height) {
    set_error(err, err_len, "more rows than the image has");
    return -1;
  }
  auto band = [w, rows, pixels] {
    const size_t nch = w->names.size(), width = (size_t)w->width;
    Imf::FrameBuffer fb;
    const Imath::V2i origin(0, w->next_row);
    for (size_t c = 0; c < nch; c++)
      fb.insert(w->names[c], Imf::Slice::Make(Imf::FLOAT, pixels + c, origin, (int64_t)width, (int64_t)rows,
                                              nch * sizeof(float), width * nch * sizeof(float)));
    w->out->setFrameBuffer(fb);
    w->out->writePixels(rows);
  };
  if (checked(w, band, err, err_len) != 0) return -1;
  w->next_row += rows;
  return 0;
}

int writer_levels(rc_image_writer *, int, const unsigned char *, char *err, size_t err_len) {
  set_error(err, err_len, "8-bit levels given to a float format");
  return -1;
}

/* Every byte on disk before the file gets its name: OpenEXR's line offsets (written as the
 * file closes), stdio's buffer, fsync. */
int writer_finish(rc_image_writer *w, char *err, size_t err_len) {
  if (w->out && w->next_row != w->height) {
    set_error(err, err_len, "the image is incomplete");
    return -1;
  }
  if (!w->out) return 0; // finished before, or a plain file
  if (checked(w, [w] { w->out.reset(); }, err, err_len) != 0) return -1;
  return rc_staged_sync(&w->staged, err, err_len);
}

int writer_close(rc_image_writer *w, int commit, char *err, size_t err_len) {
  std::unique_ptr<rc_image_writer> owned(w);
  if (!commit || writer_finish(w, err, err_len) != 0) {
    discard(w);
    return commit ? -1 : 0;
  }
  w->stream.reset();
  return rc_staged_commit(&w->staged, err, err_len);
}

rc_image_writer *file_writer_open(const char *path, const void *bytes, size_t len, char *err, size_t err_len) {
  auto w = std::make_unique<rc_image_writer>();
  if (rc_staged_open(&w->staged, path, err, err_len) != 0) return nullptr;
  if (rc_staged_write_all(&w->staged, bytes, len, err, err_len) != 0) {
    discard(w.get());
    return nullptr;
  }
  return w.release(); // no rows: finish has nothing left to do, close names it
}

const char *writer_temp_path(const rc_image_writer *w) { return rc_staged_temp_path(&w->staged); }

int can_write(const char *path) { return is_exr(path) ? 1 : 0; }

int stores_levels(const char *) { return 0; }

}  // namespace

void rc_exr_writers(rc_image_api *table) {
  table->writer_open = writer_open;
  table->writer_rows = writer_rows;
  table->writer_levels = writer_levels;
  table->writer_finish = writer_finish;
  table->writer_close = writer_close;
  table->file_writer_open = file_writer_open;
  table->writer_temp_path = writer_temp_path;
  table->can_write = can_write;
  table->stores_levels = stores_levels;
}
