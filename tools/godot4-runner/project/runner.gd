# crtforge's Godot 4 runner: runs inside Godot 4's web build (index.wasm) in headless Chromium,
# started by ../driver.mjs through ../page.html. The page hands it one job at a time as JSON
# (window.crtforgeGodotRequest) and it answers through window.crtforgeGodotDone with a JSON result:
#   {"ok": true, "count": N, "format": Image.FORMAT_* read, "errors": [...]}, the N pictures handed
#   over as downloads named "<id>-<i>.bin" (row 0 = top; RGBA8 bytes, else float32 RGBA),
#    "errors": [...]}  or  {"ok": false, "kind": "request"|"validation", "error": "...", "errors": [...]}
# "errors" are what Godot reported while the job ran (its Logger): shader errors carry the line of
# the shader they refer to. Jobs (see ../README.md for every key):
#   {"op": "shader", "shader": code, "width", "height", "input": file, "input_width",
#    "input_height", "filter": "linear"|"nearest", "params": {name: number, bool or [x, y, ...]}, "frames"}
#   {"op": "scene", "pack": path of a .pck in the engine's file system, "scene": "res://...tscn",
#    "width", "height", "inputs": file (float32 RGBA pictures, one per frame of run), "input_width", "input_height", "run": [...],
#    "capture": [...], "fps", "start_time", "fit", "params"}
#   {"op": "project", "pack": path, "scene": "res://...tscn", "width", "height", "frames"}: a scene
#    of a test's own, run until it sets `done`; what it printed comes back as "output"
extends Node

const PINNED_TIME = "crtforge_validation_time"
const TIME_ROLLOVER = 3600.0  # rendering/limits/time/time_rollover_secs


# Everything Godot reports while a job runs: script errors, shader errors (with the line of the
# shader) and the GL driver's complaints.
class ErrorLog extends Logger:
	var entries: Array = []

	func _log_error(function: String, file: String, line: int, code: String, rationale: String,
			_editor_notify: bool, error_type: int, _script_backtraces: Array) -> void:
		entries.append({"function": function, "file": file, "line": line, "code": code,
			"rationale": rationale, "type": error_type})

	var printed: PackedStringArray = []

	func _log_message(message: String, error: bool) -> void:
		if error:
			entries.append({"message": message})
		else:
			printed.append(message.trim_suffix("\n"))


var _log := ErrorLog.new()
var _window: JavaScriptObject
var _request_callback: JavaScriptObject
var _busy := false
var _packs := {}


func _ready() -> void:
	OS.add_logger(_log)
	_window = JavaScriptBridge.get_interface("window")
	_request_callback = JavaScriptBridge.create_callback(_on_request)
	_window.crtforgeGodotRequest = _request_callback
	_window.crtforgeGodotReady(JSON.stringify({
		"version": Engine.get_version_info().string,
		"hash": Engine.get_version_info().hash,
		"adapter": RenderingServer.get_video_adapter_name(),
		"api": RenderingServer.get_video_adapter_api_version(),
		"method": RenderingServer.get_current_rendering_method(),
	}))


func _on_request(args: Array) -> void:
	_run.call_deferred(str(args[0]) if args.size() > 0 else "")


func _answer(result: Dictionary) -> void:
	result["errors"] = _log.entries.duplicate()
	_window.crtforgeGodotDone(JSON.stringify(result))


func _refuse(message: String) -> Dictionary:
	return {"ok": false, "kind": "request", "error": message}


func _reject(message: String) -> Dictionary:
	return {"ok": false, "kind": "validation", "error": message}


func _run(text: String) -> void:
	if _busy:
		_answer(_refuse("a job is already running"))
		return
	_busy = true
	_log.entries.clear()
	_log.printed.clear()
	_t0 = Time.get_ticks_msec()
	_timings.clear()
	var job = JSON.parse_string(text)
	_mark("parsed")
	var result: Dictionary
	if typeof(job) != TYPE_DICTIONARY:
		result = _refuse("a job must be a JSON object")
	elif job.get("op") == "shader":
		result = await _run_shader(job)
	elif job.get("op") == "scene":
		result = await _run_scene(job)
	elif job.get("op") == "project":
		result = await _run_project(job)
	else:
		result = _refuse("unknown op '%s'" % str(job.get("op")))
	_reset()
	_busy = false
	result["timings"] = ", ".join(_timings)
	_answer(result)


# Back to the state the runner starts in: only the Picture in the viewport, with nothing on it.
func _reset() -> void:
	var viewport: SubViewport = $Viewport
	var picture: TextureRect = $Viewport/Picture
	for child in viewport.get_children():
		if child != picture:
			viewport.remove_child(child)
			child.free()
	picture.visible = true
	picture.material = null
	picture.texture = null


func _size_of(job: Dictionary, key: String, low: int) -> int:
	var v = job.get(key)
	if typeof(v) != TYPE_FLOAT or v != floor(v) or v < low or v > 16384:
		return -1
	return int(v)


# Picture `index` of a file of float32 RGBA pictures, back to back, in the engine's file system
# (the page copied it there), or null when the file is not that size.
func _picture(file: PackedByteArray, index: int, count: int, w: int, h: int) -> Image:
	var bytes := w * h * 16
	if w <= 0 or h <= 0 or file.size() != bytes * count:
		return null
	return Image.create_from_data(w, h, false, Image.FORMAT_RGBAF, file.slice(bytes * index, bytes * (index + 1)))


# name -> Variant type of every uniform the shader declares (empty when Godot refused the code).
func _uniform_types(shader: Shader) -> Dictionary:
	var types := {}
	for p in shader.get_shader_uniform_list():
		types[p["name"]] = p["type"]
	return types


func _numbers(v, count: int) -> bool:
	if typeof(v) != TYPE_ARRAY or v.size() != count:
		return false
	for c in v:
		if typeof(c) != TYPE_FLOAT and typeof(c) != TYPE_INT:
			return false
	return true


# A JSON value (number, bool, [x, y, ...]) as set_shader_parameter takes it for the uniform's
# Variant type, or null when it does not fit.
func _param_value(v, type: int):
	match type:
		TYPE_FLOAT:
			if typeof(v) == TYPE_FLOAT or typeof(v) == TYPE_INT:
				return float(v)
		TYPE_INT:
			if (typeof(v) == TYPE_FLOAT or typeof(v) == TYPE_INT) and float(v) == floor(float(v)):
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
		TYPE_VECTOR4:
			if _numbers(v, 4):
				return Vector4(v[0], v[1], v[2], v[3])
		TYPE_COLOR:
			if _numbers(v, 3):
				return Color(v[0], v[1], v[2], 1.0)
			if _numbers(v, 4):
				return Color(v[0], v[1], v[2], v[3])
	return null


# Sets the job's params on a material; with `only_declared` a name the shader lacks is skipped.
func _apply_params(material: ShaderMaterial, params: Dictionary, only_declared: bool) -> String:
	var types := _uniform_types(material.shader)
	for name in params.keys():
		if not types.has(name):
			if only_declared:
				continue
			return "param '%s': the shader declares no uniform of that name" % name
		var value = _param_value(params[name], types[name])
		if value == null:
			return "param '%s': %s does not fit the uniform's Variant type %d" % [name, JSON.stringify(params[name]), types[name]]
		material.set_shader_parameter(name, value)
	return ""


# The first shader error Godot reported during the job: {"text": "line N: message", "line": N}
# (line 0 when Godot named none), or an empty Dictionary.
func _shader_error() -> Dictionary:
	for e in _log.entries:
		if e.has("rationale") and e["function"] == "" and e["file"] == "":
			# ShaderLanguage's errors: no function or file, the line of the shader, the message.
			return {"text": "line %d: %s" % [e["line"], e["code"]], "line": e["line"]}
	for e in _log.entries:
		var text: String = e.get("rationale", e.get("message", ""))
		if text.contains("compilation failed") or text.contains("shader") or e.get("code", "").contains("shader"):
			return {"text": "%s %s" % [e.get("code", ""), text], "line": 0}
	return {}


# A job refused because of a shader error: the error's line travels as a field of its own.
func _reject_shader(what: String, error: Dictionary) -> Dictionary:
	var result := _reject(what + error["text"])
	result["line"] = error["line"]
	return result


var _timings := []
var _t0 := 0

func _mark(what: String) -> void:
	_timings.append("%s %d" % [what, Time.get_ticks_msec() - _t0])


# Hands the viewport's picture to the page as a download (JavaScriptBridge.download_buffer: a Blob
# Chromium saves into the driver's folder): no base64, no DevTools message carries the pixels.
# 8-bit pictures go as they are; others as float32 RGBA. The picture's format, or -1.
func _read_back(viewport: SubViewport, w: int, h: int, name: String) -> int:
	_mark("drawn")
	var image := viewport.get_texture().get_image()
	if image == null or image.is_empty() or image.get_width() != w or image.get_height() != h:
		return -1
	var format := image.get_format()
	if format != Image.FORMAT_RGBA8:
		image.convert(Image.FORMAT_RGBAF)
	JavaScriptBridge.download_buffer(image.get_data(), name, "application/octet-stream")
	_mark("handed")
	return format


func _run_shader(job: Dictionary) -> Dictionary:
	var w := _size_of(job, "width", 1)
	var h := _size_of(job, "height", 1)
	if w < 0 or h < 0:
		return _refuse("width and height must be integers in 1..16384")
	var frames := _size_of(job, "frames", 1)
	if frames < 0 or frames > 1000:
		return _refuse("frames must be an integer in 1..1000")
	var shader := Shader.new()
	shader.code = str(job.get("shader", ""))
	var error := _shader_error()
	if not error.is_empty():
		return _reject_shader("Godot 4 rejected the shader: ", error)
	if shader.get_mode() != Shader.MODE_CANVAS_ITEM:
		return _reject("the shader is not a canvas_item shader (Godot reads its mode as %d)" % shader.get_mode())
	var material := ShaderMaterial.new()
	material.shader = shader
	var message := _apply_params(material, job.get("params", {}), false)
	if message != "":
		return _refuse(message)
	var image: Image
	if job.has("input"):
		image = _picture(FileAccess.get_file_as_bytes(str(job["input"])), 0, 1, _size_of(job, "input_width", 1), _size_of(job, "input_height", 1))
		if image == null:
			return _refuse("input is not input_width x input_height float32 RGBA pixels")
	else:
		image = Image.create(1, 1, false, Image.FORMAT_RGBAF)
	var viewport: SubViewport = $Viewport
	var picture: TextureRect = $Viewport/Picture
	viewport.size = Vector2i(w, h)
	picture.size = Vector2(w, h)
	picture.texture = ImageTexture.create_from_image(image)
	picture.texture_filter = CanvasItem.TEXTURE_FILTER_LINEAR if job.get("filter") == "linear" else CanvasItem.TEXTURE_FILTER_NEAREST
	picture.material = material
	for _i in range(frames):
		await RenderingServer.frame_post_draw
	error = _shader_error()
	if not error.is_empty():
		return _reject_shader("Godot 4 rejected the shader: ", error)
	var format := _read_back(viewport, w, h, "%s-0.bin" % job.get("id", "job"))
	if format < 0:
		return _reject("the viewport gave no %dx%d picture" % [w, h])
	return {"ok": true, "count": 1, "format": format}


# The job's pack mounted over res:// (once per pack) and its scene loaded afresh (a later pack may
# bring new content under the same path): the PackedScene, or the refusal as a result Dictionary.
func _load_job_scene(job: Dictionary):
	var pack := str(job.get("pack", ""))
	if pack != "" and not _packs.has(pack):
		if not ProjectSettings.load_resource_pack(pack, true):
			return _refuse("Godot could not load the pack '%s'" % pack)
		_packs[pack] = true
	var packed = ResourceLoader.load(str(job.get("scene", "")), "", ResourceLoader.CACHE_MODE_REPLACE_DEEP)
	if not packed is PackedScene:
		return _reject("cannot load the scene '%s'" % str(job.get("scene", "")))
	return packed


# A scene of the job's own (a test's project around exported files): instanced in the W x H
# viewport and left running until it sets its `done` to true (at most `frames` frames); what it
# printed comes back in "output".
func _run_project(job: Dictionary) -> Dictionary:
	var w := _size_of(job, "width", 2)
	var h := _size_of(job, "height", 2)
	var frames := _size_of(job, "frames", 1)
	if w < 0 or h < 0 or frames < 0:
		return _refuse("width, height and frames must be positive integers")
	var packed = _load_job_scene(job)
	if packed is Dictionary:
		return packed
	var viewport: SubViewport = $Viewport
	$Viewport/Picture.visible = false
	viewport.size = Vector2i(w, h)
	var scene = packed.instantiate()
	viewport.add_child(scene)
	for _i in range(frames):
		await RenderingServer.frame_post_draw
		if scene.get("done") == true:
			break
	if scene.get("done") != true:
		return _reject("the scene did not set done within %d frames" % frames)
	return {"ok": true, "count": 0, "output": "\n".join(_log.printed)}


# Every ShaderMaterial of a crtforge scene's passes, or of validate's host scene.
func _scene_materials(scene: Node) -> Array:
	var out := []
	for p in scene.passes:
		var node := scene.get_node_or_null(str(p["alias"]) + "/Pass")
		if node != null and node.material is ShaderMaterial:
			out.append(node.material)
	return out


func _run_scene(job: Dictionary) -> Dictionary:
	var w := _size_of(job, "width", 2)
	var h := _size_of(job, "height", 2)
	var iw := _size_of(job, "input_width", 1)
	var ih := _size_of(job, "input_height", 1)
	if w < 0 or h < 0 or iw < 0 or ih < 0:
		return _refuse("width and height must be integers in 2..16384, input_width and input_height in 1..16384")
	var run := []
	var capture := []
	for f in job.get("run", []):
		run.append(int(f))
	for f in job.get("capture", []):
		capture.append(int(f))
	var inputs := FileAccess.get_file_as_bytes(str(job.get("inputs", "")))
	if run.is_empty():
		return _refuse("run names no frame")
	var fps := float(job.get("fps", 60.0))
	var start_time := float(job.get("start_time", 0.0))
	if fps <= 0.0 or start_time < 0.0:
		return _refuse("fps must be positive and start_time not negative")
	var packed = _load_job_scene(job)
	if packed is Dictionary:
		return packed
	var scene = packed.instantiate()
	if scene == null or scene.get("passes") == null:
		return _reject("the scene '%s' is not a crtforge scene" % str(job.get("scene", "")))
	var image := _picture(inputs, 0, run.size(), iw, ih)
	if image == null:
		scene.free()
		return _refuse("inputs[0] is not input_width x input_height float32 RGBA pixels")
	var source := ImageTexture.create_from_image(image)
	var viewport: SubViewport = $Viewport
	$Viewport/Picture.visible = false
	viewport.size = Vector2i(w, h)
	scene.playing = false
	if job.has("fit"):
		scene.fit = str(job["fit"])
	viewport.add_child(scene)
	scene.size = Vector2(w, h)
	scene.source = source
	var materials := _scene_materials(scene)
	for material in materials:
		var message := _apply_params(material, job.get("params", {}), true)
		if message != "":
			return _refuse(message)
	var count := 0
	var format := -1
	for i in range(run.size()):
		var frame: int = run[i]
		if i > 0:
			image = _picture(inputs, i, run.size(), iw, ih)
			if image == null:
				return _refuse("inputs[%d] is not input_width x input_height float32 RGBA pixels" % i)
			source.update(image)
		scene.seconds = start_time + frame / fps
		scene.frame = int(job.get("frame_count_base", 0)) + frame
		# Godot's TIME is the wall clock: the engine pins it through this uniform instead, wrapped as
		# Godot wraps TIME.
		for material in materials:
			if _uniform_types(material.shader).has(PINNED_TIME):
				material.set_shader_parameter(PINNED_TIME, fmod(start_time + frame / fps, TIME_ROLLOVER))
		_mark("frame")
		await RenderingServer.frame_post_draw
		var error := _shader_error()
		if not error.is_empty():
			return _reject_shader("Godot 4 rejected a shader of the scene: ", error)
		if not frame in capture:
			continue
		format = _read_back(viewport, w, h, "%s-%d.bin" % [job.get("id", "job"), count])
		if format < 0:
			return _reject("the viewport gave no %dx%d picture at frame %d" % [w, h, frame])
		count += 1
	return {"ok": true, "count": count, "format": format}
