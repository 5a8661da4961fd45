#!/usr/bin/env python3
"""Emitter-level mutation testing: how many wrong emitters does `crtforge validate` catch?

Each mutation below edits one line of an emitter (targets/) or of a file users receive (Godot's
inspector metadata, manifest.json), the kind of slip a change to the WGSL printer, the Godot
compiler, a writer's options or the manifest could make. The script clones the repository's
committed state into a scratch folder, builds it once, then for each mutation: applies it, rebuilds
(incremental), runs `crtforge validate` on the mutated target for a few presets, and reverts it.
A mutation is killed when validate fails (a compile or render check); it survives when every
check passes. Prints one line per mutation and the kill rate. Not run in CI (it rebuilds the
product once per mutation: about a minute each on 2 cores after a first full build).

usage: bench/emitter_mutations.py [--keep DIR] [--only SUBSTRING of a description or a file]
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

# (file, find, replace, target, presets, what it breaks). `find` must occur exactly once.
MUTATIONS = [
    ("targets/wgsl/wgsl_printer.cpp", 'case spv::OpFSub: case spv::OpISub: binary("-")',
     'case spv::OpFSub: case spv::OpISub: binary("+")', "wgsl", "classic,crt-shadow-mask", "subtraction printed as addition"),
    ("targets/wgsl/wgsl_printer_builtins.cpp", '{GLSLstd450Floor, "floor"}', '{GLSLstd450Floor, "ceil"}',
     "wgsl", "crt-shadow-mask,atari-16", "floor printed as ceil"),
    ("targets/wgsl/wgsl_printer_builtins.cpp", '{GLSLstd450Fract, "fract"}', '{GLSLstd450Fract, "trunc"}',
     "wgsl", "crt-aperture-grille,webgpu-post,quiet-frame", "fract printed as trunc"),
    ("targets/wgsl/wgsl_printer.cpp", 'case spv::OpFOrdLessThan: compare("<")', 'case spv::OpFOrdLessThan: compare("<=")',
     "wgsl", "crt-shadow-mask,atari-crt,super-win,atari-ntsc,atari-chain", "a < comparison printed as <= (differs only at equality)"),
    ("targets/wgsl/wgsl_printer.cpp", 'case spv::OpSelect: call("select", {2, 1, 0})',
     'case spv::OpSelect: call("select", {1, 2, 0})', "wgsl", "crt-shadow-mask,classic,super-win", "select arms swapped"),
    ("targets/wgsl/wgsl_printer_builtins.cpp", 'define(inst, Expr::primary("smoothstep(" + texts() + ")"), true);',
     'define(inst, Expr::primary("sqrt(smoothstep(" + texts() + "))"), true);',
     "wgsl", "quiet-frame,super-win,stage-vignette-quiet-frame", "smoothstep's curve bent (sqrt of it)"),
    ("targets/wgsl/wgsl_printer_builtins.cpp", '{GLSLstd450FMin, "min"}', '{GLSLstd450FMin, "max"}',
     "wgsl", "super-win,stage-color-grade-lut32,stage-crt-screen-perspective", "min printed as max"),
    ("targets/godot/godot_compiler.cpp", 'constexpr const char* kTau = "6.28318530717959";',
     'constexpr const char* kTau = "6.2832";', "godot3", "crt-pulse", "the TIME-wrap rounding uses a short 2*pi"),
    ("targets/godot/godot_compiler.cpp", 'return screen_mode() ? "round(1.0 / SCREEN_PIXEL_SIZE)" : "round(1.0 / abs(', 'return screen_mode() ? "round(0.5 / SCREEN_PIXEL_SIZE)" : "round(1.0 / abs(',
     "godot3", "classic,crt-shadow-mask,webgpu-post", "screen mode's output size halved"),
    ("targets/godot/godot_compiler.cpp", '"round(1.0 / abs(vec2(dFdx(UV.x), dFdy(UV.y))))"',
     '"floor(1.0 / abs(vec2(dFdx(UV.x), dFdy(UV.y))))"', "godot4", "classic,crt-shadow-mask,webgpu-post",
     "node mode's output size floored instead of rounded"),
    # Godot inspector metadata (issue 29): validate's inspector check reads them back from the files.
    ("targets/godot/godot_compiler.cpp", 'fmt::format(" : hint_range({}, {}, {})", float_literal(*s.min), float_literal(*s.max), float_literal(step))',
     'fmt::format(" : hint_range({}, {}, {})", float_literal(*s.max), float_literal(*s.min), float_literal(step))',
     "godot4", "classic", "a float slider's min and max swapped"),
    ("targets/godot/godot_compiler.cpp", 'float_literal(*s.max), float_literal(step));', 'float_literal(*s.max), float_literal(step * 2.0));',
     "godot3", "classic", "a float slider's step doubled"),
    ("targets/godot/godot_compiler.cpp", 'static_cast<int64_t>(*s.max), static_cast<int64_t>(step))',
     'static_cast<int64_t>(*s.max) - 1, static_cast<int64_t>(step))', "godot4", "atari-16", "an int slider's max one short"),
    ("targets/godot/godot_compiler.cpp", 'value = fmt::format("vec3({}, {}, {})", float_literal(c[0]), float_literal(c[1]), float_literal(c[2]));',
     'value = fmt::format("vec3({}, {}, {})", float_literal(c[2]), float_literal(c[1]), float_literal(c[0]));',
     "godot4", "super-win", "a colour default's red and blue swapped"),
    ("targets/godot/godot_compiler.cpp", 'value = fmt::format("vec4({}, {}, {}, 1.0)"', 'value = fmt::format("vec4({}, {}, {}, 0.0)"',
     "godot3", "super-win", "a colour default's alpha 0"),
    ("targets/godot/godot_writer.cpp", 'fmt::format("Color({}, {}, {}, 1)", literal((*c)[0]), literal((*c)[1]), literal((*c)[2]))',
     'fmt::format("Color({}, {}, {}, 1)", literal((*c)[2]), literal((*c)[1]), literal((*c)[0]))',
     "godot4", "super-win", "a material colour's red and blue swapped"),
    ("targets/godot/godot_writer.cpp", 'fmt::format("Color( {}, {}, {}, 1 )"', 'fmt::format("Color( {}, {}, {}, 0 )"',
     "godot3", "super-win", "a material colour's alpha 0"),
    ("targets/godot/godot_writer.cpp", 'if (auto d = std::get_if<double>(&p->value)) value = literal(*d);',
     'if (auto d = std::get_if<double>(&p->value)) value = literal(*d * 0.5);', "godot4", "classic", "material values halved"),
    # manifest.json (issue 29): validate's Vulkan renders bind and fill the passes from it.
    ("generator/manifest.cpp", 'member["offset"] = m.offset;', 'member["offset"] = m.offset + 4;',
     "spirv", "classic,atari-16", "a uniform member's offset one float late"),
    ("generator/manifest.cpp", 'json texture{{"name", t.name}, {"set", t.set}, {"binding", t.binding}};',
     'json texture{{"name", t.name}, {"set", t.set}, {"binding", t.binding + 1}};', "spirv", "atari-ntsc,super-win",
     "a texture's binding off by one"),
    ("generator/manifest.cpp", 'out["size"] = block.size;', 'out["size"] = block.size - 4;', "spirv", "classic",
     "the uniform block's size one float short"),
    # The shipped WebGPU driver (issue 29): validate renders every WGSL preset through the npm package
    # the export writes, whose crt-webgpu.mjs is this file (embedded at build time).
    ("examples/webgpu/crt-webgpu.mjs", "for (const alias of feedback) {", "for (const alias of []) {",
     "wgsl", "super-win", "feedback textures never swapped"),
    ("examples/webgpu/crt-webgpu.mjs", "const filter = unfilterable || t.filter === 'nearest' ? 'nearest' : 'linear';",
     "const filter = unfilterable || t.filter === 'linear' ? 'nearest' : 'linear';", "wgsl", "super-win,crt-shadow-mask",
     "every sampler's filter inverted"),
    ("examples/webgpu/crt-webgpu.mjs", "const values = Array.isArray(value) ? [...value] : [value];",
     "const values = Array.isArray(value) ? [...value].reverse() : [value];", "wgsl", "classic",
     "a vector uniform's components reversed"),
    ("examples/webgpu/crt-webgpu.mjs", "history.unshift(oldest);", "history.push(oldest);", "wgsl", "graph-history",
     "the original's history frames in the wrong order"),
    ("examples/webgpu/crt-webgpu.mjs", "const TAU = 2 * Math.PI;", "const TAU = Math.PI;", "wgsl", "crt-pulse",
     "time wrapped early (half a period)"),
    ("examples/webgpu/crt-webgpu.mjs", "const seconds = time ?? frame / (scene.fps ?? 60);",
     "const seconds = time ?? (frame + 1) / (scene.fps ?? 60);", "wgsl", "crt-pulse", "time a frame ahead"),
    ("examples/webgpu/crt-webgpu.mjs", "const frameCount = pass.frameCountMod > 0 ? frame % pass.frameCountMod : frame;",
     "const frameCount = frame;", "wgsl", "graph-history", "a pass's frame_count_mod ignored"),
    ("examples/webgpu/crt-webgpu.mjs", "return clamp(lround(base * s.factor), 1, 16384);",
     "return clamp(Math.floor(base * s.factor), 1, 16384);", "wgsl", "super-win", "a pass's size floored, not rounded"),
    # The npm package's framework adapters (issue 29): validate's `web = [...]` goldens run each
    # through examples/webgpu/check.mjs on the framework's own device.
    ("examples/webgpu/package/framework-pass.mjs", "height: target.height, frame, time, fit });",
     "height: target.height, frame, time });", "wgsl", "crt-pulse", "an adapter drops the display fit"),
    ("examples/webgpu/package/framework-pass.mjs", "height: target.height, frame, time, fit });",
     "height: target.height, frame, fit });", "wgsl", "crt-pulse", "an adapter drops the app's time"),
    ("examples/webgpu/package/framework-pass.mjs", "height: target.height, frame, time, fit });",
     "height: target.height, frame: frame + 1, time, fit });", "wgsl", "super-win,graph-history",
     "an adapter's frame number one ahead"),
    ("examples/webgpu/package/framework-pass.mjs", "for (const [param, value] of values) scene.setParam(param, value);",
     "void values;", "wgsl", "crt-pulse", "params set before a second target format are not replayed on its scene"),
    ("examples/webgpu/package/babylon.mjs", "beforeSubmit: () => engine.flushFramebuffer() });", "beforeSubmit: () => {} });",
     "wgsl", "super-win,graph-history", "Babylon's recorded drawing not flushed before the pass reads it"),
    ("examples/webgpu/package/pixi.mjs", "const source = texture?.source ?? texture;", "const source = texture;",
     "wgsl", "graph-history", "Pixi's RenderTexture taken for its TextureSource"),
    ("examples/webgpu/package/three.mjs", "if (!texture) {\n      const previous", "if (texture) {\n      const previous",
     "wgsl", "graph-history", "three's texture of a RenderTarget made only when it already exists"),
    # Godot scene wiring and host uniforms (issue 29): the exported .tscn and its pipeline scripts.
    ("targets/godot/godot_scene.cpp", "for (int n = history; n >= 1; --n) viewport(",
     "for (int n = 1; n <= history; ++n) viewport(", "godot4", "graph-history",
     "history viewports drawn newest first (each copies a frame too new)"),
    ("targets/godot/crtforge_pipeline3.gd", 'copy.texture = _original() if n == 1 else get_node("history-%d" % (n - 1)).get_texture()',
     'copy.texture = _original() if n <= 2 else get_node("history-%d" % (n - 1)).get_texture()', "godot3", "graph-history",
     "a history frame copied from the original, not the next newer frame"),
    ("targets/godot/crtforge_pipeline4.gd", 'material.set_shader_parameter("frameCount", frame % mod if mod > 0 else frame)',
     'material.set_shader_parameter("frameCount", frame)', "godot4", "graph-history", "a pass's frame_count_mod ignored"),
    ("targets/hlsl/hlsl_writer.cpp", "common.vertex.flip_vert_y = options.flip_vertex_y && stage == ShaderStage::Vertex;",
     "common.vertex.flip_vert_y = !options.flip_vertex_y && stage == ShaderStage::Vertex;", "hlsl50",
     "classic,webgpu-post", "HLSL's clip-space y flip inverted"),
    ("targets/glsl/glsl_writer.cpp", "o.vertex.flip_vert_y = options.flip_vertex_y && stage == ShaderStage::Vertex;",
     "o.vertex.flip_vert_y = !options.flip_vertex_y && stage == ShaderStage::Vertex;", "glsl330",
     "classic,webgpu-post", "GLSL's clip-space y flip inverted"),
]


def run(cmd, cwd, quiet=True):
    return subprocess.run(cmd, cwd=cwd, shell=True, text=True,
                          stdout=subprocess.PIPE if quiet else None, stderr=subprocess.STDOUT if quiet else None)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--keep", help="build in this folder and keep it (reused by a later run)")
    parser.add_argument("--only", default="", help="only mutations whose description or file contains this")
    args = parser.parse_args()
    repo = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
    work = os.path.abspath(args.keep) if args.keep else tempfile.mkdtemp(prefix="crtforge-mutations-")
    os.makedirs(work, exist_ok=True)
    src = os.path.join(work, "src")
    if not os.path.isdir(src):
        if run(f"git clone -q {repo} {src}", cwd=work).returncode != 0:
            sys.exit("bench: cannot clone the repository")
    # The npm packages (Dawn; Godot 4's web build; the screenshot tool) are not in git: the clone
    # uses the working tree's (scripts/setup.sh installs them).
    for tool in ("wgsl-runner", "godot4-runner", "screenshot"):
        modules = os.path.join(repo, "tools", tool, "node_modules")
        link = os.path.join(src, "tools", tool, "node_modules")
        if os.path.isdir(modules) and not os.path.exists(link):
            os.symlink(modules, link)
    # The product's own build (the clone shares nothing with the working tree's build/).
    build = os.path.join(src, "build")
    print("bench: building the unmutated product once (several minutes on 2 cores)...", flush=True)
    if run("cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null && cmake --build build -j2 --target crtforge",
           cwd=src).returncode != 0:
        sys.exit("bench: the unmutated product does not build")
    killed = 0
    chosen = [m for m in MUTATIONS if args.only in m[5] or args.only in m[0]]
    for path, find, replace, target, presets, what in chosen:
        file = os.path.join(src, path)
        original = open(file).read()
        if original.count(find) != 1:
            print(f"  ERROR    {what}: '{find}' is not exactly once in {path}")
            continue
        open(file, "w").write(original.replace(find, replace))
        try:
            built = run("cmake --build build -j2 --target crtforge", cwd=src)
            if built.returncode != 0:
                verdict, detail = "killed", "the product no longer builds"
            else:
                result = run(f"./build/crtforge validate --target {target} --preset {presets} --second-device none -j2", cwd=src)
                failed = [l for l in result.stdout.splitlines() if l.startswith("FAIL")]
                verdict = "killed" if result.returncode != 0 else "SURVIVED"
                detail = failed[0][:110] if failed else result.stdout.strip().splitlines()[-1][:110]
        finally:
            open(file, "w").write(original)
        killed += verdict == "killed"
        print(f"  {verdict:8} {target:8} {what}: {detail}", flush=True)
    run("cmake --build build -j2 --target crtforge", cwd=src)
    if not args.keep:
        shutil.rmtree(work, ignore_errors=True)
    print(f"emitter mutations: {killed} of {len(chosen)} killed ({100.0 * killed / max(1, len(chosen)):.0f}%)")
    return 0 if killed == len(chosen) else 1


if __name__ == "__main__":
    sys.exit(main())
