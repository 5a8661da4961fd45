# crtforge's Godot 3 runner (Godot 3.2+, GLES3). Renders one canvas_item shader over one picture in
# an off-screen Viewport and writes the pixels it reads back. Arguments come after `--`, each as
# `--key=value` (or `--key value`):
#   --shader=PATH        Godot 3 canvas_item shader source (required)
#   --width=W --height=H output size in pixels (required)
#   --output=PATH        where the pixels go (required; format below)
#   --input=PATH         raw little-endian float32 RGBA, rows top first, IW*IH*16 bytes
#                        (optional: without it the shader gets a 1x1 transparent-black texture)
#   --input-width=IW --input-height=IH   size of --input (required with it)
#   --filter=linear|nearest              sampling of TEXTURE (default linear)
#   --params=PATH        JSON object: uniform name -> value, converted by the uniform's type:
#                        float/int <- number (an int must be integral), bool <- true/false,
#                        vec4 : hint_color <- [r, g, b] (alpha 1) or [r, g, b, a], vec3 <- [x, y, z],
#                        vec2 <- [x, y], vec4 <- [x, y, z, w]. A name the shader does not declare
#                        is an error.
#   --frames=N           frames rendered before the read-back (default 2)
# Serve mode: --serve=DIR [--parent=PID]; then jobs as files in DIR (see _serve below).
# Scene mode, instead of --shader: a crtforge scene exported into this project (res://addons/...):
#   --scene=res://PATH.tscn   the scene; it fills the W x H viewport and `source` gets the inputs
#   --inputs=PATH        raw float32 RGBA pictures, IW x IH each, one per frame of --run
#   --run=0,1,2          the frames drawn, in order (the scene's `frame` is set to each)
#   --capture=1,2        the frames whose picture is written, to <--output><frame>.raw
#   --fps=60             the frame rate: the scene's `seconds` is start + frame / fps, and a uniform
#                        crtforge_validation_time standing for TIME gets that mod 3600
#   --start-time=0       seconds at frame 0
#   --frame-count-base=0 the scene's frame (shaders' frameCount) at frame 0
#   --params=PATH        as above, set on every pass that declares the uniform
#   --fit=aspect         overrides the scene's display fit (stretch, aspect, integer)
# Output file: 24-byte header, then W*H*4 little-endian float32, RGBA, row 0 = TOP of the picture:
#   "CRTG3PX1" | u32 width | u32 height | u32 Image.FORMAT_* the viewport gave | u32 0
# Exit code 0 on success; on failure a one-line "crtforge-godot3-runner: ..." on stderr and a
# non-zero exit code (2 = bad arguments, files or params, 3 = the shader was rejected or the
# render or the read-back failed, 4 = a GDScript error in this runner).
extends Node

const MAGIC = "CRTG3PX1"
const PREFIX = "crtforge-godot3-runner: "


func _ready():
	var status = yield(_run(), "completed")
	if typeof(status) != TYPE_INT:  # a script error inside _run() returns null
		status = _fail(4, "internal error in runner.gd (see the SCRIPT ERROR above)")
	get_tree().quit(status)


func _fail(code, message):
	printerr(PREFIX + message)
	return code


# Parses the user arguments (after "--") into a Dictionary of key -> String.
func _parse_args():
	var args = Array(OS.get_cmdline_args())
	var opts = {}
	var start = args.find("--")
	var i = start + 1 if start >= 0 else 0
	while i < args.size():
		var arg = args[i]
		if not arg.begins_with("--"):
			return "unexpected argument '%s'" % arg
		var key = arg.substr(2, arg.length() - 2)
		var eq = key.find("=")
		if eq >= 0:
			opts[key.substr(0, eq)] = key.substr(eq + 1, key.length() - eq - 1)
		elif i + 1 < args.size():
			opts[key] = args[i + 1]
			i += 1
		else:
			return "argument '%s' has no value" % arg
		i += 1
	return opts


func _positive_int(opts, key, required):
	if not opts.has(key):
		return -1 if required else 0
	var text = opts[key]
	if not text.is_valid_integer() or int(text) <= 0 or int(text) > 16384:
		return -1
	return int(text)


func _read_text(path):
	var f = File.new()
	if f.open(path, File.READ) != OK:
		return null
	var text = f.get_as_text()
	f.close()
	return text


# name -> Variant type (TYPE_REAL, TYPE_INT, TYPE_BOOL, TYPE_COLOR, ...) of every uniform the shader
# declares. Empty when Godot's shader parser rejected the code. (Shader.has_param() is not usable
# here: in 3.2 it only answers after a material has listed its properties.)
func _uniform_types(shader):
	var types = {}
	for p in VisualServer.shader_get_param_list(shader.get_rid()):
		types[p["name"]] = p["type"]
	return types


func _type_name(type):
	match type:
		TYPE_BOOL: return "bool"
		TYPE_INT: return "int"
		TYPE_REAL: return "float"
		TYPE_VECTOR2: return "vec2"
		TYPE_VECTOR3: return "vec3"
		TYPE_PLANE: return "vec4"
		TYPE_COLOR: return "vec4 : hint_color"
	return "Variant type %d" % type


func _is_number(v):
	return typeof(v) == TYPE_REAL or typeof(v) == TYPE_INT


func _numbers(v, count):
	if typeof(v) != TYPE_ARRAY or v.size() != count:
		return false
	for c in v:
		if not _is_number(c):
			return false
	return true


# The value to hand set_shader_param() for a JSON value and the uniform's type, or an error
# message (String prefixed by "!").
func _convert_param(name, v, type):
	match type:
		TYPE_REAL:
			if _is_number(v):
				return float(v)
		TYPE_INT:
			if _is_number(v) and float(v) == floor(float(v)):
				return int(v)
		TYPE_BOOL:
			if typeof(v) == TYPE_BOOL:
				return v
		TYPE_VECTOR2:
			if _numbers(v, 2):
				return Vector2(v[0], v[1])
		TYPE_VECTOR3:
			if _numbers(v, 3):
				return Vector3(v[0], v[1], v[2])
		TYPE_COLOR:
			if _numbers(v, 3):
				return Color(v[0], v[1], v[2], 1.0)
			if _numbers(v, 4):
				return Color(v[0], v[1], v[2], v[3])
		TYPE_PLANE:
			if _numbers(v, 4):
				return Plane(v[0], v[1], v[2], v[3])
		_:
			return "!uniform '%s' has a type this runner does not set (%s)" % [name, _type_name(type)]
	return "!param '%s': JSON value %s does not fit the uniform's type %s" % [name, JSON.print(v), _type_name(type)]


# Sets every entry of the params JSON on the material. Returns "" or an error message.
func _apply_params(material, types, path):
	var text = _read_text(path)
	if text == null:
		return "cannot read params file '%s'" % path
	var parsed = JSON.parse(text)
	if parsed.error != OK:
		return "params file '%s' line %d: %s" % [path, parsed.error_line, parsed.error_string]
	if typeof(parsed.result) != TYPE_DICTIONARY:
		return "params file '%s' is not a JSON object" % path
	var params = parsed.result
	for name in params.keys():
		if not types.has(name):
			return "param '%s': the shader declares no uniform of that name" % name
		var value = _convert_param(name, params[name], types[name])
		if typeof(value) == TYPE_STRING and value.begins_with("!"):
			return value.substr(1, value.length() - 1)
		material.set_shader_param(name, value)
	return ""


# Builds the input texture; returns an ImageTexture or an error message (String).
func _make_texture(opts, linear):
	var flags = Texture.FLAG_FILTER if linear else 0
	var image = Image.new()
	if not opts.has("input"):
		image.create(1, 1, false, Image.FORMAT_RGBAF)
		image.fill(Color(0, 0, 0, 0))
	else:
		var iw = _positive_int(opts, "input-width", true)
		var ih = _positive_int(opts, "input-height", true)
		if iw < 0 or ih < 0:
			return "--input needs --input-width and --input-height (1..16384)"
		var f = File.new()
		if f.open(opts["input"], File.READ) != OK:
			return "cannot read input file '%s'" % opts["input"]
		var expected = iw * ih * 16
		var length = f.get_len()
		if length != expected:
			f.close()
			return "input file '%s' has %d bytes, %dx%d float32 RGBA needs %d" % [opts["input"], length, iw, ih, expected]
		var bytes = f.get_buffer(expected)
		f.close()
		image.create_from_data(iw, ih, false, Image.FORMAT_RGBAF, bytes)
	var texture = ImageTexture.new()
	texture.create_from_image(image, flags)
	return texture


func _write_output(path, image, source_format):
	var f = File.new()
	if f.open(path, File.WRITE) != OK:
		return "cannot write output file '%s'" % path
	f.store_buffer(MAGIC.to_ascii())
	f.store_32(image.get_width())
	f.store_32(image.get_height())
	f.store_32(source_format)
	f.store_32(0)
	f.store_buffer(image.get_data())
	var err = f.get_error()
	f.close()
	if err != OK:
		return "writing output file '%s' failed (error %d)" % [path, err]
	return ""


func _run():
	yield(get_tree(), "idle_frame")  # makes _run() a coroutine in every path
	var opts = _parse_args()
	if typeof(opts) == TYPE_STRING:
		return _fail(2, opts)
	if opts.has("serve"):
		return yield(_serve(opts["serve"], int(opts.get("parent", "0"))), "completed")
	return yield(_run_job(opts), "completed")


# One job: a shader over a picture, or a crtforge scene.
func _run_job(opts):
	yield(get_tree(), "idle_frame")
	if opts.has("scene"):
		return yield(_run_scene(opts), "completed")
	return yield(_run_shader(opts), "completed")


# Serve mode (--serve=DIR [--parent=PID]): jobs arrive as files DIR/job-0.json, job-1.json, ...
# (Godot 3.2 reads neither stdin nor a named pipe), each a JSON object of the same keys as the
# command line (values as strings), written elsewhere and renamed in whole; after each,
# "crtforge-godot3-done: <exit code>" on stderr. Ends when DIR/quit appears or process PID is gone.
# While waiting the main loop is held in a sleep, so an idle runner draws nothing. Files a job names
# are read when it runs; resources loaded by path (scenes, shaders of scenes) stay cached, so a
# path must keep its content for the life of the process.
func _serve(dir, parent):
	yield(get_tree(), "idle_frame")
	var files = File.new()
	var folders = Directory.new()
	var n = 0
	while true:
		var path = "%s/job-%d.json" % [dir, n]
		while not files.file_exists(path):
			if files.file_exists(dir + "/quit") or (parent > 0 and not folders.dir_exists("/proc/%d" % parent)):
				return 0
			OS.delay_msec(2)
		n += 1
		var line = _read_text(path)
		folders.remove(path)
		if line == null:
			line = ""
		var parsed = JSON.parse(line)
		var status = 2
		if parsed.error != OK or typeof(parsed.result) != TYPE_DICTIONARY:
			_fail(2, "serve: a job must be one JSON object per line")
		else:
			status = yield(_run_job(parsed.result), "completed")
			if typeof(status) != TYPE_INT:
				status = _fail(4, "internal error in runner.gd (see the SCRIPT ERROR above)")
		_reset()
		printerr("crtforge-godot3-done: %d" % status)


# Back to the state a fresh runner starts in: only the Picture in the viewport, with nothing on it.
func _reset():
	var viewport = $Viewport
	var picture = $Viewport/Picture
	for child in viewport.get_children():
		if child != picture:
			viewport.remove_child(child)
			child.free()
	picture.visible = true
	picture.material = null
	picture.texture = null


func _run_shader(opts):
	yield(get_tree(), "idle_frame")
	for key in opts.keys():
		if not key in ["shader", "input", "width", "height", "input-width", "input-height", "filter", "params", "output", "frames"]:
			return _fail(2, "unknown argument '--%s'" % key)
	for key in ["shader", "width", "height", "output"]:
		if not opts.has(key):
			return _fail(2, "missing --%s" % key)
	var w = _positive_int(opts, "width", true)
	var h = _positive_int(opts, "height", true)
	if w < 0 or h < 0:
		return _fail(2, "--width and --height must be integers in 1..16384")
	var frames = 2
	if opts.has("frames"):
		frames = _positive_int(opts, "frames", true)
		if frames < 0 or frames > 1000:
			return _fail(2, "--frames must be an integer in 1..1000")
	var filter = opts.get("filter", "linear")
	if filter != "linear" and filter != "nearest":
		return _fail(2, "--filter must be linear or nearest, not '%s'" % filter)

	var code = _read_text(opts["shader"])
	if code == null:
		return _fail(2, "cannot read shader file '%s'" % opts["shader"])
	var shader = Shader.new()
	shader.code = code
	if shader.get_mode() != Shader.MODE_CANVAS_ITEM:
		return _fail(3, "the shader is not a canvas_item shader (no 'shader_type canvas_item;')")
	# Godot 3 gives a script no compile status. A copy with one extra uniform appended tells:
	# Godot's parser reports no uniforms at all for code it rejects (its SHADER ERROR line is on
	# stderr). Errors the GL driver raises later, at draw time, only show on stderr.
	var probe = Shader.new()
	probe.code = code + "\nuniform float crtforge_runner_probe_;\n"
	if not _uniform_types(probe).has("crtforge_runner_probe_"):
		return _fail(3, "Godot rejected the shader (see the SHADER ERROR line above)")
	var material = ShaderMaterial.new()
	material.shader = shader

	var texture = _make_texture(opts, filter == "linear")
	if typeof(texture) == TYPE_STRING:
		return _fail(2, texture)
	if opts.has("params"):
		var message = _apply_params(material, _uniform_types(shader), opts["params"])
		if message != "":
			return _fail(2, message)

	# Godot 3.2 (GLES3) silently renders nothing into a viewport narrower than 2 pixels in either
	# direction (its half-size effect buffers get a zero size), so such outputs are drawn into a
	# viewport padded to 2 and cropped. The picture sits at the BOTTOM-left of the padded viewport,
	# where FRAGCOORD (origin bottom-left) matches the unpadded size; SCREEN_PIXEL_SIZE and
	# SCREEN_UV then describe the padded viewport.
	var vw = max(w, 2)
	var vh = max(h, 2)
	var viewport = $Viewport
	var picture = $Viewport/Picture
	viewport.size = Vector2(vw, vh)
	picture.texture = texture
	picture.material = material
	picture.rect_position = Vector2(0, vh - h)
	picture.rect_size = Vector2(w, h)

	for _i in range(frames):
		yield(VisualServer, "frame_post_draw")

	var image = viewport.get_texture().get_data()
	if image == null or image.is_empty():
		return _fail(3, "the viewport gave no pixels")
	if image.get_width() != vw or image.get_height() != vh:
		return _fail(3, "the viewport gave %dx%d pixels, expected %dx%d" % [image.get_width(), image.get_height(), vw, vh])
	var source_format = image.get_format()
	# Godot 3 hands a viewport's texture back bottom row first (GL order) unless
	# render_target_v_flip is set; flipping here keeps the render target itself untouched.
	image.flip_y()
	if vw != w or vh != h:
		image = image.get_rect(Rect2(0, vh - h, w, h))
	image.convert(Image.FORMAT_RGBAF)
	var message = _write_output(opts["output"], image, source_format)
	if message != "":
		return _fail(3, message)
	return 0


# ---- scene mode: a crtforge scene (<preset>.tscn) exported into this project ----------------

func _int_list(text):
	var out = []
	for part in text.split(",", false):
		if not part.is_valid_integer() or int(part) < 0:
			return null
		out.append(int(part))
	return out


# Every ShaderMaterial of the scene's passes, with the uniform types of its shader.
func _scene_materials(scene):
	var out = []
	for p in scene.passes:
		var material = scene.get_node(p["alias"] + "/Pass").material
		out.append([material, _uniform_types(material.shader)])
	return out


func _run_scene(opts):
	yield(get_tree(), "idle_frame")
	for key in opts.keys():
		if not key in ["scene", "width", "height", "inputs", "input-width", "input-height", "run", "capture", "fps", "start-time", "frame-count-base", "params", "output", "fit"]:
			return _fail(2, "unknown argument '--%s'" % key)
	for key in ["scene", "width", "height", "inputs", "input-width", "input-height", "run", "capture", "output"]:
		if not opts.has(key):
			return _fail(2, "missing --%s" % key)
	var w = _positive_int(opts, "width", true)
	var h = _positive_int(opts, "height", true)
	var iw = _positive_int(opts, "input-width", true)
	var ih = _positive_int(opts, "input-height", true)
	if w < 2 or h < 2 or iw < 0 or ih < 0:
		return _fail(2, "--width and --height must be integers in 2..16384, --input-width and --input-height in 1..16384")
	var run = _int_list(opts["run"])
	var capture = _int_list(opts["capture"])
	if run == null or run.empty() or capture == null:
		return _fail(2, "--run and --capture must be comma-separated frame numbers")
	var fps = float(opts.get("fps", "60"))
	if fps <= 0:
		return _fail(2, "--fps must be positive")
	var start_time = float(opts.get("start-time", "0"))
	var frame_count_base = int(opts.get("frame-count-base", "0"))
	if start_time < 0:
		return _fail(2, "--start-time must not be negative")

	var packed = load(opts["scene"])
	if packed == null or not packed is PackedScene:
		return _fail(3, "cannot load the scene '%s'" % opts["scene"])
	var scene = packed.instance()
	if scene == null or scene.get("passes") == null:
		return _fail(3, "the scene '%s' is not a crtforge scene" % opts["scene"])
	var materials = []

	# The frames' inputs: one float32 RGBA picture per entry of --run, in that order.
	var f = File.new()
	if f.open(opts["inputs"], File.READ) != OK:
		return _fail(2, "cannot read inputs file '%s'" % opts["inputs"])
	var picture_bytes = iw * ih * 16
	if f.get_len() != picture_bytes * run.size():
		f.close()
		return _fail(2, "inputs file '%s' has %d bytes, %d pictures of %dx%d need %d" % [opts["inputs"], f.get_len(), run.size(), iw, ih, picture_bytes * run.size()])
	var image = Image.new()
	image.create_from_data(iw, ih, false, Image.FORMAT_RGBAF, f.get_buffer(picture_bytes))
	var source = ImageTexture.new()
	source.create_from_image(image, 0)

	var viewport = $Viewport
	$Viewport/Picture.visible = false
	viewport.size = Vector2(w, h)
	scene.playing = false
	if opts.has("fit"):
		if not opts["fit"] in ["stretch", "aspect", "integer"]:
			return _fail(2, "--fit must be stretch, aspect or integer")
		scene.fit = opts["fit"]
	viewport.add_child(scene)
	scene.rect_size = Vector2(w, h)
	scene.source = source
	materials = _scene_materials(scene)
	if opts.has("params"):
		for entry in materials:
			var message = _apply_scene_params(entry[0], entry[1], opts["params"])
			if message != "":
				f.close()
				return _fail(2, message)

	for i in range(run.size()):
		var frame = run[i]
		if i > 0:
			image.create_from_data(iw, ih, false, Image.FORMAT_RGBAF, f.get_buffer(picture_bytes))
			source.set_data(image)
		scene.seconds = start_time + frame / fps  # the pipeline hands its shaders hostTime from it
		scene.frame = frame_count_base + frame
		# Godot's TIME is the wall clock: the engine pins it through this uniform instead, wrapped
		# as Godot wraps TIME (rendering/limits/time/time_rollover_secs, 3600 s by default).
		for entry in materials:
			if entry[1].has("crtforge_validation_time"):
				entry[0].set_shader_param("crtforge_validation_time", fmod(start_time + frame / fps, 3600.0))
		yield(VisualServer, "frame_post_draw")
		if not frame in capture:
			continue
		var out = viewport.get_texture().get_data()
		if out == null or out.is_empty() or out.get_width() != w or out.get_height() != h:
			f.close()
			return _fail(3, "the viewport gave no %dx%d picture at frame %d" % [w, h, frame])
		var source_format = out.get_format()
		out.flip_y()
		out.convert(Image.FORMAT_RGBAF)
		var message = _write_output("%s%d.raw" % [opts["output"], frame], out, source_format)
		if message != "":
			f.close()
			return _fail(3, message)
	f.close()
	return 0


# The params JSON set on one pass's material: only the uniforms that pass declares.
func _apply_scene_params(material, types, path):
	var text = _read_text(path)
	if text == null:
		return "cannot read params file '%s'" % path
	var parsed = JSON.parse(text)
	if parsed.error != OK or typeof(parsed.result) != TYPE_DICTIONARY:
		return "params file '%s' is not a JSON object" % path
	for name in parsed.result.keys():
		if not types.has(name):
			continue
		var value = _convert_param(name, parsed.result[name], types[name])
		if typeof(value) == TYPE_STRING and value.begins_with("!"):
			return value.substr(1, value.length() - 1)
		material.set_shader_param(name, value)
	return ""
