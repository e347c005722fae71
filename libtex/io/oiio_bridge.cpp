// oiio_bridge.cpp - OpenImageIO behind a C interface, loaded with dlopen
//
// Textura's only C++ file.  It is built as textura-oiio.so so that a tool
// on the EXR path never loads OpenImageIO (its start-up and shared libraries
// are many times a tool's own: doc/performance.md); see oiio_bridge.h for the interface.
#include <cstdio>
#include <cstdlib>
#include <cerrno>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

extern "C" {
#include "io/oiio_bridge.h"
}

using namespace OIIO;

// Some codecs (libpng, libtiff) print their own complaints on stderr; the
// tools promise one line per error, so mute fd 2 while OpenImageIO works.
struct quiet_stderr {
    int saved = -1;
    quiet_stderr()
    {
        int null = open("/dev/null", O_WRONLY);
        fflush(stderr);
        if (null >= 0) {
            saved = dup(2);
            dup2(null, 2);
            close(null);
        }
    }
    ~quiet_stderr()
    {
        if (saved >= 0) {
            dup2(saved, 2);
            close(saved);
        }
    }
};

struct tex_oiio_in {
    std::unique_ptr<ImageInput> in;
    std::unique_ptr<Filesystem::IOMemReader> mem;
    std::string spill; // a temporary file for formats that can't read from memory
};

static void say(char *err, size_t n, const std::string &s)
{
    std::string t = s;
    // One line: OpenImageIO's messages may span several.
    for (char &c : t)
        if (c == '\n')
            c = ' ';
    while (!t.empty() && t.back() == ' ')
        t.pop_back();
    snprintf(err, n, "%s", t.empty() ? "unreadable image" : t.c_str());
}

// A message about a temporary copy of standard input must not name the
// copy: the caller says "standard input".
static std::string unspill(std::string s, const std::string &spill)
{
    for (size_t at; !spill.empty() && (at = s.find(spill)) != std::string::npos;)
        s.replace(at, spill.size(), "the data");
    return s;
}

static tex_oiio_in *b_open(const char *path, const void *mem, size_t len, const char *ext, int *w,
                           int *h, int *nc, char *err, size_t errlen)
{
    quiet_stderr mute;
    auto r = std::make_unique<tex_oiio_in>();
    std::string name = path ? path : std::string("stdin.") + ext;

    if (!path) {
        // Read from memory where the plugin can; some (PNM in 2.4) claim
        // IOProxy support but fail to open, so fall back to a temporary file.
        r->mem.reset(new Filesystem::IOMemReader(mem, len));
        auto probe = ImageInput::create(name, false, nullptr, r->mem.get());
        if (probe && probe->supports("ioproxy")) {
            ImageSpec config;
            r->in = ImageInput::open(name, &config, r->mem.get());
            (void)geterror(); // a failure here is not the user's error yet
        }
        if (!r->in) {
            const char *dir = getenv("TMPDIR");
            std::string tmpl = std::string(dir && *dir ? dir : "/tmp") + "/textura-XXXXXX." + ext;
            std::vector<char> buf(tmpl.begin(), tmpl.end());
            buf.push_back('\0');
            int fd = mkstemps(buf.data(), (int)strlen(ext) + 1);
            if (fd < 0) {
                say(err, errlen, "cannot create a temporary file");
                return nullptr;
            }
            const char *p = (const char *)mem;
            size_t left = len;
            while (left > 0) {
                ssize_t k = write(fd, p, left);
                if (k <= 0)
                    break;
                p += k;
                left -= (size_t)k;
            }
            close(fd);
            r->spill = buf.data();
            r->in = ImageInput::open(r->spill);
        }
    } else {
        r->in = ImageInput::open(name);
    }
    if (!r->in) {
        say(err, errlen, unspill(geterror(), r->spill));
        if (!r->spill.empty())
            unlink(r->spill.c_str());
        return nullptr;
    }
    const ImageSpec &s = r->in->spec();
    *w = s.width;
    *h = s.height;
    *nc = s.nchannels;
    if (s.depth > 1) {
        say(err, errlen, "volume images are not texture maps");
        return nullptr;
    }
    return r.release();
}

static int b_read(tex_oiio_in *r, float *px, int nc, char *err, size_t errlen)
{
    quiet_stderr mute;
    if (!r->in->read_image(0, 0, 0, nc, TypeDesc::FLOAT, px)) {
        say(err, errlen, unspill(r->in->geterror(), r->spill));
        return -1;
    }
    return 0;
}

static void b_close(tex_oiio_in *r)
{
    if (r->in)
        r->in->close();
    if (!r->spill.empty())
        unlink(r->spill.c_str());
    delete r;
}

/* Every byte of b to the file at path, or a message: a short write (ENOSPC) fails. */
static int write_checked(const char *path, const std::vector<unsigned char> &b, char *err,
                         size_t errlen)
{
    int fd = open(path, O_WRONLY | O_TRUNC | O_CLOEXEC);
    const unsigned char *p = b.data();
    size_t left = b.size();

    if (fd < 0) {
        say(err, errlen, std::string("cannot open: ") + strerror(errno));
        return -1;
    }
    while (left > 0) {
        ssize_t k = write(fd, p, left);
        if (k < 0 && errno == EINTR)
            continue;
        if (k <= 0) {
            say(err, errlen, std::string("write failed: ") + strerror(k < 0 ? errno : ENOSPC));
            close(fd);
            return -1;
        }
        p += k;
        left -= (size_t)k;
    }
    if (close(fd) < 0) {
        say(err, errlen, std::string("write failed: ") + strerror(errno));
        return -1;
    }
    return 0;
}

static int write_direct(ImageOutput *out, const char *path, const ImageSpec &spec, TypeDesc t,
                        const void *px, char *err, size_t errlen)
{
    if (!out->open(path, spec) || !out->write_image(t, px) || !out->close()) {
        say(err, errlen, out->geterror());
        return -1;
    }
    return 0;
}

static int b_write(const char *path, const char *format_name, const void *px, int w, int h,
                   int nc, int bits, char *err, size_t errlen)
{
    quiet_stderr mute;
    TypeDesc t = bits == 8 ? TypeDesc::UINT8 : bits == 16 ? TypeDesc::UINT16 : TypeDesc::FLOAT;
    std::string probe = std::string("x.") + format_name;
    auto out = ImageOutput::create(probe);

    if (!out) {
        say(err, errlen, geterror());
        return -1;
    }
    ImageSpec spec(w, h, nc, t);
    if (nc == 2) {
        spec.channelnames = {"Y", "A"};
        spec.alpha_channel = 1;
    }
    // OIIO's BMP and TGA writers ignore a short write (a full disk left a
    // corrupt file and success): where the writer takes a proxy, it encodes
    // into memory and every byte goes to the file here, checked.
    if (!out->supports("ioproxy"))
        return write_direct(out.get(), path, spec, t, px, err, errlen);
    std::vector<unsigned char> bytes;
    Filesystem::IOVecOutput mem(bytes);
    if (!out->set_ioproxy(&mem) || !out->open(path, spec) || !out->write_image(t, px) ||
        !out->close()) {
        say(err, errlen, out->geterror());
        return -1;
    }
    return write_checked(path, bytes, err, errlen);
}

// The one exported symbol; const would otherwise give it internal linkage in C++.
extern "C" __attribute__((visibility("default"))) const struct tex_oiio_bridge tex_oiio_bridge;
const struct tex_oiio_bridge tex_oiio_bridge = {TEX_OIIO_BRIDGE_VERSION, b_open, b_read, b_close,
                                                b_write};
