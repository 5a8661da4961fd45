# crtforge_pipeline.gd (Godot 4): runs a crtforge scene, <preset>.tscn, exported beside it.
# Written by crtforge; the same file for every preset. Each scene carries its pipeline in the
# properties below; this script sizes the passes, wires their textures and counts frames.
#
# The scene's nodes, in tree order (the order the passes must be drawn in):
#   previous-<alias>  a copy of pass <alias>'s output of the previous frame (for feedback reads),
#                     taken before the passes run;
#   <alias>           one SubViewport per pass, its TextureRect "Pass" carrying the pass's
#                     ShaderMaterial over the pass's main input;
#   history-<N>       the original of N frames ago (copied after the passes, oldest first);
#   crt-background, crt-display   the last pass at the screen's rectangle, over black.
# Extra textures are sampler uniforms whose filter and repeat hints the shaders carry; the main
# input's filter and repeat are the "Pass" node's texture_filter and texture_repeat.
#
# Use: instance the scene and set `source` to the picture, e.g. the ViewportTexture of the
# SubViewport your game draws into (keep it before this scene in the tree, so it is drawn first).
# The scene fills its parent; resize it as any Control. `frame` counts frames (shaders get it as
# frameCount) and `seconds` the time since start (shaders get it reduced exactly, as hostTime); set
# `playing = false` to drive both yourself.
extends Control

@export var source: Texture2D = null:
	set(texture):
		source = texture
		if is_inside_tree():
			_wire()
			_layout()
@export var playing := true
@export var frame := 0:
	set(value):
		frame = value
		if is_inside_tree():
			_apply_frame()
@export var seconds := 0.0:  # a 64-bit float: exact enough for years
	set(value):
		seconds = value
		if is_inside_tree():
			_apply_frame()

# The pipeline (written by crtforge).
@export var pixel_aspect := Vector2(1, 1)
@export var screen_aspect := Vector2(0, 0)  # (0, 0): the source's display aspect
@export var fit := "stretch"  # stretch | aspect | integer
@export var passes: Array = []  # per pass: alias, scale, hdr, input, textures, frame_count_mod, frame_count, sizes
@export var feedback: Array = []  # aliases of passes read as the previous frame
@export var history := 0  # frames of the original kept
@export var luts: Dictionary = {}  # name -> {path, filter, wrap}

var _lut_textures := {}
var _placeholder: Texture2D = null


func _ready() -> void:
	_load_luts()
	_wire()
	_layout()
	resized.connect(_layout)
	_apply_frame()


func _process(delta: float) -> void:
	_apply_frame()
	if playing:
		frame += 1
		seconds += delta


# The texture the original comes from: `source`, or black until one is set.
func _original() -> Texture2D:
	if source != null:
		return source
	if _placeholder == null:
		var image := Image.create(1, 1, false, Image.FORMAT_RGBA8)
		image.fill(Color(0, 0, 0, 1))
		_placeholder = ImageTexture.create_from_image(image)
	return _placeholder


# A LUT from its PNG: the imported texture when the editor has imported it (what an exported game
# has), else the file read directly (a project run without the editor's import step). A LUT read
# through a mip chain ("mipmap") gets one here, whatever the import settings say.
func _load_luts() -> void:
	for name in luts.keys():
		var path: String = luts[name]["path"]
		var mipmap: bool = luts[name].get("mipmap", false)
		var image: Image = null
		if ResourceLoader.exists(path):
			var imported: Texture2D = load(path)
			if not mipmap:
				_lut_textures[name] = imported
				continue
			if imported != null:
				image = imported.get_image()
		if image == null:
			image = Image.load_from_file(path)
		if image == null:
			push_error("crtforge: cannot load LUT '%s' from %s" % [name, path])
			continue
		if image.is_compressed():
			image.decompress()  # a VRAM-compressed import: convert() needs plain texels
		image.convert(Image.FORMAT_RGBA8)
		if mipmap:
			image.generate_mipmaps()
		_lut_textures[name] = ImageTexture.create_from_image(image)


func _texture(spec: Dictionary) -> Texture2D:
	match spec["from"]:
		"original":
			var back := int(spec.get("frames_back", 0))
			return _original() if back == 0 else (get_node("history-%d" % back) as SubViewport).get_texture()
		"pass":
			return (get_node(spec["name"]) as SubViewport).get_texture()
		"feedback":
			return (get_node("previous-" + spec["name"]) as SubViewport).get_texture()
		"lut":
			return _lut_textures.get(spec["name"])
	return null


func _sampling(rect: TextureRect, spec: Dictionary) -> void:
	rect.texture_filter = CanvasItem.TEXTURE_FILTER_LINEAR if spec.get("filter", "linear") == "linear" else CanvasItem.TEXTURE_FILTER_NEAREST
	match spec.get("wrap", "clamp_to_edge"):
		"repeat":
			rect.texture_repeat = CanvasItem.TEXTURE_REPEAT_ENABLED
		"mirrored_repeat":
			rect.texture_repeat = CanvasItem.TEXTURE_REPEAT_MIRROR
		_:
			rect.texture_repeat = CanvasItem.TEXTURE_REPEAT_DISABLED


func _wire() -> void:
	for p in passes:
		var rect := get_node(p["alias"] + "/Pass") as TextureRect
		rect.texture = _texture(p["input"])
		_sampling(rect, p["input"])
		for name in p["textures"].keys():
			(rect.material as ShaderMaterial).set_shader_parameter(name, _texture(p["textures"][name]))
	for alias in feedback:
		var copy := get_node("previous-" + alias + "/Copy") as TextureRect
		copy.texture = (get_node(alias) as SubViewport).get_texture()
	for n in range(1, history + 1):
		var copy := get_node("history-%d/Copy" % n) as TextureRect
		copy.texture = _original() if n == 1 else (get_node("history-%d" % (n - 1)) as SubViewport).get_texture()
	var display := get_node("crt-display") as TextureRect
	display.texture = (get_node(passes[passes.size() - 1]["alias"]) as SubViewport).get_texture()


func _apply_frame() -> void:
	for p in passes:
		var material := (get_node(p["alias"] + "/Pass") as TextureRect).material as ShaderMaterial
		if p["frame_count"]:
			var mod := int(p["frame_count_mod"])
			material.set_shader_parameter("frameCount", frame % mod if mod > 0 else frame)
		if p.has("time_speed"):
			material.set_shader_parameter("hostTime", _reduced_time(material, p["time_speed"]))


# `seconds` reduced by one period of the pass's angular speed (a uniform's name or a number) in
# double precision, so the shader's phase time * speed is exact at any hour: what crtforge's
# other hosts give their shaders as time (crtforge::shader_time()).
func _reduced_time(material: ShaderMaterial, speed: Variant) -> float:
	if typeof(speed) == TYPE_STRING:
		speed = material.get_shader_parameter(speed)
	var s := absf(float(speed))
	if s == 0.0:
		return seconds
	return fposmod(seconds * s, TAU) / s


# ---- geometry: the same rules as crtforge's scene model (generator/scene.cpp) ----

func _screen_aspect(source_size: Vector2) -> float:
	if screen_aspect.x > 0:
		return screen_aspect.x / screen_aspect.y
	return source_size.x * pixel_aspect.x / (source_size.y * pixel_aspect.y)


func _centred(display: Vector2i, width: int, height: int) -> Rect2i:
	width = clampi(width, 1, display.x)
	height = clampi(height, 1, display.y)
	return Rect2i((display.x - width) / 2, (display.y - height) / 2, width, height)


func _screen_rect(display: Vector2i, source_size: Vector2) -> Rect2i:
	if fit == "stretch" or source_size.x <= 0 or source_size.y <= 0:
		return Rect2i(Vector2i(), display)
	var aspect := _screen_aspect(source_size)
	if fit == "integer":
		var k := display.y / int(source_size.y)
		while k >= 1:
			var height := k * int(source_size.y)
			var width := int(round(height * aspect))
			if width <= display.x:
				return _centred(display, width, height)
			k -= 1
	if display.x >= display.y * aspect:
		return _centred(display, int(round(display.y * aspect)), display.y)
	return _centred(display, display.x, int(round(display.x / aspect)))


func _axis(type: String, factor: float, input: float, viewport: float) -> int:
	var base := 1.0
	if type == "source":
		base = input
	elif type == "viewport":
		base = viewport
	return clampi(int(round(base * factor)), 1, 16384)


func _pass_sizes(source_size: Vector2, screen: Vector2i) -> Array:
	var sizes := {}
	var ordered := []
	for p in passes:
		var input := source_size
		var from: Dictionary = p["input"]
		if (from["from"] == "pass" or from["from"] == "feedback") and sizes.has(from["name"]):
			input = Vector2(sizes[from["name"]])
		var s: Array = p["scale"]
		var size := Vector2i(_axis(s[0], float(s[1]), input.x, screen.x), _axis(s[2], float(s[3]), input.y, screen.y))
		sizes[p["alias"]] = size
		ordered.append(size)
	# The last pass draws the screen, whatever its scale says.
	ordered[ordered.size() - 1] = Vector2i(maxi(screen.x, 1), maxi(screen.y, 1))
	return ordered


# Godot draws nothing into a viewport under 2 pixels: a pass 1 pixel wide or tall gets 2, both
# computing its one pixel (its shader holds that axis at the centre; readers are told 1).
func _resize(viewport: SubViewport, child: Control, size: Vector2i) -> void:
	size = Vector2i(maxi(size.x, 2), maxi(size.y, 2))
	viewport.size = size
	child.position = Vector2()
	child.size = Vector2(size)


func _layout() -> void:
	var display := Vector2i(maxi(1, roundi(size.x)), maxi(1, roundi(size.y)))
	var source_size := _original().get_size()
	var screen := _screen_rect(display, source_size)
	var sizes := _pass_sizes(source_size, screen.size)
	for i in range(passes.size()):
		var viewport := get_node(passes[i]["alias"]) as SubViewport
		_resize(viewport, viewport.get_node("Pass"), sizes[i])
		if passes[i].get("sizes", false):  # a program pass: its vertex stage has no other way to know them
			var material := (viewport.get_node("Pass") as TextureRect).material as ShaderMaterial
			material.set_shader_parameter("outputSize", Vector2(sizes[i]))
			material.set_shader_parameter("viewportSize", Vector2(screen.size))
	for alias in feedback:
		var copy := get_node("previous-" + alias) as SubViewport
		_resize(copy, copy.get_node("Copy"), (get_node(alias) as SubViewport).size)
	for n in range(1, history + 1):
		var copy := get_node("history-%d" % n) as SubViewport
		_resize(copy, copy.get_node("Copy"), Vector2i(source_size))
	var background := get_node("crt-background") as Control
	background.position = Vector2()
	background.size = Vector2(display)
	var shown := get_node("crt-display") as Control
	shown.position = Vector2(screen.position)
	shown.size = Vector2(screen.size)
