#!/usr/bin/env python3
"""Test pictures for the RetroArch runner, and a reader for its PNG screenshots (stdlib only).

  pictures.py bars OUT.ppm [W H]     colour bars + grey ramp + fine lines (default 320x240)
  pictures.py ramp OUT.pam           256x4 RGBA: R=x, G=255-x, B=(7x)&255, A=(x*3)&255 (row y adds y)
  pictures.py checker OUT.ppm [N]    NxN black/white texel checkerboard (default 4)
  pictures.py values SHOT.png        decodes the top cell row written by values.slang
  pictures.py compare A.png B.(png|ppm|pam) [--alpha]
                                     per-channel max difference (RGB, or B's alpha against A's grey)
  pictures.py psnr A.png B.png       PSNR in dB of B against A (RGB, 8-bit; inf when identical)
  pictures.py info SHOT.png          size and the first pixels of the first and last rows
"""
import struct
import sys
import zlib


def write_ppm(path, w, h, rgb):
    with open(path, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (w, h))
        f.write(bytes(rgb))


def write_pam(path, w, h, rgba):
    with open(path, "wb") as f:
        f.write(b"P7\nWIDTH %d\nHEIGHT %d\nDEPTH 4\nMAXVAL 255\nTUPLTYPE RGB_ALPHA\nENDHDR\n" % (w, h))
        f.write(bytes(rgba))


def read_pnm(path):
    """Returns (w, h, channels, bytes) of a P6 PPM or P7 PAM as written above."""
    data = open(path, "rb").read()
    if data.startswith(b"P6"):
        parts = data.split(maxsplit=4)
        w, h = int(parts[1]), int(parts[2])
        return w, h, 3, parts[4][: w * h * 3]
    head, body = data.split(b"ENDHDR\n", 1)
    fields = dict(line.split(b" ", 1) for line in head.split(b"\n")[1:] if b" " in line)
    w, h, d = int(fields[b"WIDTH"]), int(fields[b"HEIGHT"]), int(fields[b"DEPTH"])
    return w, h, d, body[: w * h * d]


def read_png(path):
    """Returns (w, h, channels, bytes) of an 8-bit RGB or RGBA, non-interlaced PNG."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat = 8, b""
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos : pos + 8])
        chunk = data[pos + 8 : pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, (depth, ctype, interlace)
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + n
    ch = 3 if ctype == 2 else 4
    raw, stride = zlib.decompress(idat), w * ch
    out, prev = bytearray(), bytearray(stride)
    for y in range(h):
        ftype, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - ch] if i >= ch else 0
            b, c = prev[i], prev[i - ch] if i >= ch else 0
            if ftype == 1:
                line[i] = (line[i] + a) & 255
            elif ftype == 2:
                line[i] = (line[i] + b) & 255
            elif ftype == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif ftype == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += line
        prev = line
    return w, h, ch, bytes(out)


def bars(w, h):
    """Top half: 8 colour bars; then a horizontal grey ramp; bottom quarter: fine lines
    (1-px vertical, 1-px horizontal, a checker) so scanline/mask/blur effects are visible.
    A red marker square sits in the top-left corner to show orientation."""
    bar_colours = [(255, 255, 255), (255, 255, 0), (0, 255, 255), (0, 255, 0),
                   (255, 0, 255), (255, 0, 0), (0, 0, 255), (0, 0, 0)]
    px = bytearray()
    for y in range(h):
        for x in range(w):
            if x < w // 16 and y < h // 12:
                c = (255, 0, 0) if (x + y) % 2 == 0 else (255, 128, 0)
            elif y < h // 2:
                c = bar_colours[x * 8 // w]
            elif y < h * 3 // 4:
                v = x * 255 // (w - 1)
                c = (v, v, v)
            elif x < w // 3:
                c = (255, 255, 255) if x % 2 == 0 else (0, 0, 0)
            elif x < 2 * w // 3:
                c = (255, 255, 255) if y % 2 == 0 else (0, 0, 0)
            else:
                c = (255, 255, 255) if (x + y) % 2 == 0 else (0, 0, 0)
            px += bytes(c)
    return px


def main(argv):
    cmd = argv[1]
    if cmd == "bars":
        w, h = (int(argv[3]), int(argv[4])) if len(argv) > 4 else (320, 240)
        write_ppm(argv[2], w, h, bars(w, h))
    elif cmd == "ramp":
        px = bytearray()
        for y in range(4):
            for x in range(256):
                px += bytes(((x + y) & 255, (255 - x) & 255, (7 * x + y) & 255, (3 * x + 5 * y) & 255))
        write_pam(argv[2], 256, 4, px)
    elif cmd == "checker":
        n = int(argv[3]) if len(argv) > 3 else 4
        px = bytearray()
        for y in range(n):
            for x in range(n):
                px += b"\xff\xff\xff" if (x + y) % 2 == 0 else b"\x00\x00\x00"
        write_ppm(argv[2], n, n, px)
    elif cmd == "values":
        w, h, ch, px = read_png(argv[2])
        names = ["marker 0x123456", "FrameCount", "SourceSize.x", "SourceSize.y", "OriginalSize.x",
                 "OriginalSize.y", "OutputSize.x", "OutputSize.y", "FinalViewportSize.x",
                 "FinalViewportSize.y", "SourceSize.z*2^24", "SourceSize.w*2^24", "OutputSize.z*2^24",
                 "OutputSize.w*2^24", "FinalViewportSize.z*2^24", "FinalViewportSize.w*2^24",
                 "FrameDirection+1000", "textureSize(Source).x", "textureSize(Source).y", "end marker 0xABCDEF"]
        for row_name, y in (("first PNG row", 3), ("last PNG row", h - 4)):
            vals = []
            for k in range(len(names)):
                i = (y * w + k * 8 + 4) * ch
                vals.append(px[i] << 16 | px[i + 1] << 8 | px[i + 2])
            ok = vals[0] == 0x123456 and vals[-1] == 0xABCDEF
            print("%s (%dx%d PNG): %s" % (row_name, w, h, "markers found" if ok else "no markers"))
            if ok:
                for n, v in zip(names, vals):
                    extra = " (= 1/%.6f)" % (16777216.0 / v) if "2^24" in n and v else ""
                    print("  %-26s %d%s" % (n, v, extra))
    elif cmd == "compare":
        w, h, ch, pa = read_png(argv[2])
        path_b = argv[3]
        wb, hb, chb, pb = read_png(path_b) if path_b.endswith(".png") else read_pnm(path_b)
        assert (w, h) == (wb, hb), "sizes differ: %dx%d vs %dx%d" % (w, h, wb, hb)
        use_alpha = "--alpha" in argv
        worst, count = [0, 0, 0], 0
        for i in range(w * h):
            for c in range(3):
                va = pa[i * ch + c]
                vb = pb[i * chb + (3 if use_alpha else c)]
                d = abs(va - vb)
                worst[c] = max(worst[c], d)
                count += d != 0
        print("max |diff| per channel:", worst, "differing channel values:", count)
    elif cmd == "psnr":
        # PSNR (dB) of B against A over RGB, 8-bit: inf when identical.
        import math
        w, h, ch, pa = read_png(argv[2])
        wb, hb, chb, pb = read_png(argv[3])
        assert (w, h) == (wb, hb), "sizes differ: %dx%d vs %dx%d" % (w, h, wb, hb)
        se = 0
        for i in range(w * h):
            for c in range(3):
                d = pa[i * ch + c] - pb[i * chb + c]
                se += d * d
        mse = se / (w * h * 3)
        print("inf" if mse == 0 else "%.2f" % (10 * math.log10(255 * 255 / mse)))
    elif cmd == "info":
        w, h, ch, px = read_png(argv[2])
        print("%dx%d, %d channels" % (w, h, ch))
        for name, y in (("row 0", 0), ("row %d" % (h - 1), h - 1)):
            print(" ", name, [tuple(px[(y * w + x) * ch : (y * w + x) * ch + ch]) for x in range(4)])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
