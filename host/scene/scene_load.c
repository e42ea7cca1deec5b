/* scene_load.c: the front door of scene loading (rc_scene_load): reads the file, tells
 * its format (by the name, else by the first character), and hands the text to that
 * format's parser (scene_json.c, scene_cse167.c). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/json_locate.h"
#include "scene/mesh.h"
#include "scene/scene.h"

/* Scene files larger than this are refused before reading (a mesh belongs in a mesh file). */
#define RC_MAX_SCENE_FILE_BYTES (256u << 20)

typedef enum { FORMAT_BY_CONTENT, FORMAT_JSON, FORMAT_TEST } scene_format;

/* The format the name gives; a stream (standard input, a pipe) has no extension. */
static scene_format format_of_name(const char *path) {
  if (rc_has_extension(path, ".test")) return FORMAT_TEST;
  if (rc_has_extension(path, ".json")) return FORMAT_JSON;
  return FORMAT_BY_CONTENT;
}

/* Without an extension, the first character that is not white space tells: '{' is JSON,
 * anything else the .test format. */
static bool starts_like_json(const char *text, size_t len) {
  size_t i = 0;
  while (i < len && strchr(" \t\r\n", text[i]) && text[i]) i++;
  return i < len && text[i] == '{';
}

rc_status rc_scene_load(const char *path, const rc_load_options *options, rc_scene *scene) {
  memset(scene, 0, sizeof *scene);
  if (rc_has_extension(path, ".vkrs")) {
    /* Read as text it would fail at its first byte, with a message about JSON. */
    fprintf(stderr, "%s: error: a prepared scene (vkraycast prepare) is rendered by `render`; this command reads the "
            "scene file it was prepared from\n", path);
    return RC_ERR_INPUT;
  }
  char *text = NULL;
  size_t len = 0;
  rc_status st = rc_read_input(path, "scene file", RC_MAX_SCENE_FILE_BYTES, &text, &len);
  if (st != RC_OK) return st;
  /* Messages name standard input "<stdin>"; meshes are then found from the current folder. */
  const char *name = strcmp(path, "-") == 0 ? RC_STDIN_NAME : path;
  scene_format format = format_of_name(path);
  if (len == 0 && format == FORMAT_BY_CONTENT) {
    fprintf(stderr, "%s: error: the scene is empty (nothing was read)\n", name);
    free(text);
    return RC_ERR_INPUT;
  }
  bool test = format == FORMAT_TEST || (format == FORMAT_BY_CONTENT && !starts_like_json(text, len));
  st = test ? rc_scene_parse_cse167(name, text, len, scene) : rc_scene_parse_json(name, text, len, options, scene);
  rc_mesh_cache_clear();
  free(text);
  size_t inline_skipped = scene->degenerate_triangles - scene->degenerate_in_meshes;
  if (st == RC_OK && inline_skipped)
    fprintf(stderr, "%s: warning: skipped %zu degenerate (zero-area) triangle%s\n", name, inline_skipped,
            inline_skipped == 1 ? "" : "s");
  return st;
}
