/* crtforge still-picture libretro core.
 *
 * The "game" is a picture file: binary PPM (P6, maxval 255) or PAM (P7, DEPTH 3 or 4, maxval 255;
 * DEPTH 4 = RGB_ALPHA). Every retro_run presents that picture unchanged, as XRGB8888 at exactly the
 * file's size, so a shader preset sees a fixed Original/Source of a size we choose. The core keeps
 * no state besides the picture and uses no clock, input or randomness: every frame is identical
 * and every run is the same. No audio is produced (the runner uses RetroArch's null audio driver).
 *
 * The fourth byte of each pixel (the "X" of XRGB8888) carries the PAM's alpha (255 for PPM and
 * RGB PAM), so a probe shader can tell whether RetroArch passes it through or forces it to 1.
 */
#include <libretro.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static retro_environment_t env_cb;
static retro_video_refresh_t video_cb;
static retro_input_poll_t input_poll_cb;

static uint32_t *pixels; /* width * height, 0xAARRGGBB in native byte order */
static unsigned width, height;

/* ---- picture file parsing ---------------------------------------------------------------- */

/* Reads one whitespace-delimited header token, skipping '#' comments (PNM header syntax). */
static int read_token(FILE *f, char *out, size_t size)
{
   int c;
   size_t n = 0;
   for (;;) {
      c = fgetc(f);
      if (c == '#')
         while (c != '\n' && c != EOF)
            c = fgetc(f);
      if (c == EOF)
         return 0;
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r')
         break;
   }
   while (c != EOF && c != ' ' && c != '\t' && c != '\n' && c != '\r') {
      if (n + 1 < size)
         out[n++] = (char)c;
      c = fgetc(f);
   }
   out[n] = '\0';
   /* The single whitespace after the last header token was consumed: the raster starts next. */
   return 1;
}

static int read_uint(FILE *f, unsigned *v)
{
   char tok[32], *end;
   unsigned long x;
   if (!read_token(f, tok, sizeof tok))
      return 0;
   x = strtoul(tok, &end, 10);
   if (*end || x == 0 || x > 16384)
      return 0;
   *v = (unsigned)x;
   return 1;
}

/* Parses the header; on success the stream stands at the first raster byte. */
static int read_header(FILE *f, unsigned *w, unsigned *h, unsigned *depth)
{
   char tok[64];
   unsigned maxval = 0;
   if (!read_token(f, tok, sizeof tok))
      return 0;
   if (!strcmp(tok, "P6")) { /* P6 <w> <h> <maxval> */
      *depth = 3;
      return read_uint(f, w) && read_uint(f, h) && read_uint(f, &maxval) && maxval == 255;
   }
   if (strcmp(tok, "P7")) /* PAM: KEY VALUE lines up to ENDHDR */
      return 0;
   *w = *h = *depth = 0;
   while (read_token(f, tok, sizeof tok)) {
      if (!strcmp(tok, "ENDHDR"))
         return *w && *h && (*depth == 3 || *depth == 4) && maxval == 255;
      if (!strcmp(tok, "WIDTH")) { if (!read_uint(f, w)) return 0; }
      else if (!strcmp(tok, "HEIGHT")) { if (!read_uint(f, h)) return 0; }
      else if (!strcmp(tok, "DEPTH")) { if (!read_uint(f, depth)) return 0; }
      else if (!strcmp(tok, "MAXVAL")) { if (!read_uint(f, &maxval)) return 0; }
      else if (!strcmp(tok, "TUPLTYPE")) { if (!read_token(f, tok, sizeof tok)) return 0; }
      else return 0;
   }
   return 0;
}

static int load_picture(const char *path)
{
   unsigned w, h, depth;
   size_t i, n;
   unsigned char *raw;
   FILE *f = fopen(path, "rb");
   if (!f)
      return 0;
   if (!read_header(f, &w, &h, &depth)) {
      fclose(f);
      return 0;
   }
   n = (size_t)w * h;
   raw = malloc(n * depth);
   pixels = malloc(n * sizeof *pixels);
   if (!raw || !pixels || fread(raw, depth, n, f) != n) {
      free(raw);
      free(pixels);
      pixels = NULL;
      fclose(f);
      return 0;
   }
   fclose(f);
   for (i = 0; i < n; i++) {
      const unsigned char *p = raw + i * depth;
      uint32_t a = depth == 4 ? p[3] : 255;
      pixels[i] = a << 24 | (uint32_t)p[0] << 16 | (uint32_t)p[1] << 8 | p[2];
   }
   free(raw);
   width = w;
   height = h;
   return 1;
}

/* ---- libretro API -------------------------------------------------------------------------- */

RETRO_API unsigned retro_api_version(void) { return RETRO_API_VERSION; }

RETRO_API void retro_set_environment(retro_environment_t cb)
{
   bool no_game = false; /* a picture is required */
   env_cb = cb;
   cb(RETRO_ENVIRONMENT_SET_SUPPORT_NO_GAME, &no_game);
}

RETRO_API void retro_set_video_refresh(retro_video_refresh_t cb) { video_cb = cb; }
RETRO_API void retro_set_audio_sample(retro_audio_sample_t cb) { (void)cb; }
RETRO_API void retro_set_audio_sample_batch(retro_audio_sample_batch_t cb) { (void)cb; }
RETRO_API void retro_set_input_poll(retro_input_poll_t cb) { input_poll_cb = cb; }
RETRO_API void retro_set_input_state(retro_input_state_t cb) { (void)cb; }

RETRO_API void retro_init(void) {}
RETRO_API void retro_deinit(void) {}

RETRO_API void retro_get_system_info(struct retro_system_info *info)
{
   memset(info, 0, sizeof *info);
   info->library_name = "crtforge still";
   info->library_version = "1";
   info->valid_extensions = "ppm|pam|pnm";
   info->need_fullpath = true; /* we read the file ourselves, no need for RetroArch to load it */
   info->block_extract = true;
}

RETRO_API void retro_get_system_av_info(struct retro_system_av_info *info)
{
   memset(info, 0, sizeof *info);
   info->geometry.base_width = info->geometry.max_width = width;
   info->geometry.base_height = info->geometry.max_height = height;
   info->geometry.aspect_ratio = (float)width / (float)height; /* square pixels */
   info->timing.fps = 60.0;
   info->timing.sample_rate = 48000.0;
}

RETRO_API bool retro_load_game(const struct retro_game_info *game)
{
   enum retro_pixel_format fmt = RETRO_PIXEL_FORMAT_XRGB8888;
   if (!game || !game->path || !env_cb(RETRO_ENVIRONMENT_SET_PIXEL_FORMAT, &fmt))
      return false;
   return load_picture(game->path) ? true : false;
}

RETRO_API void retro_run(void)
{
   input_poll_cb();
   video_cb(pixels, width, height, width * sizeof *pixels);
}

RETRO_API void retro_unload_game(void)
{
   free(pixels);
   pixels = NULL;
}

RETRO_API void retro_reset(void) {}
RETRO_API void retro_set_controller_port_device(unsigned port, unsigned device) { (void)port; (void)device; }
RETRO_API bool retro_load_game_special(unsigned type, const struct retro_game_info *info, size_t num)
{
   (void)type; (void)info; (void)num;
   return false;
}
RETRO_API unsigned retro_get_region(void) { return RETRO_REGION_NTSC; }
RETRO_API size_t retro_serialize_size(void) { return 0; }
RETRO_API bool retro_serialize(void *data, size_t size) { (void)data; (void)size; return false; }
RETRO_API bool retro_unserialize(const void *data, size_t size) { (void)data; (void)size; return false; }
RETRO_API void retro_cheat_reset(void) {}
RETRO_API void retro_cheat_set(unsigned index, bool enabled, const char *code) { (void)index; (void)enabled; (void)code; }
RETRO_API void *retro_get_memory_data(unsigned id) { (void)id; return NULL; }
RETRO_API size_t retro_get_memory_size(unsigned id) { (void)id; return 0; }
