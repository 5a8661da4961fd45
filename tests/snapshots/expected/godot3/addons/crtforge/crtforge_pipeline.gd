# crtforge_pipeline.gd (Godot 3): runs a crtforge scene, <preset>.tscn, exported beside it.
# Written by crtforge; the same file for every preset. Each scene carries its pipeline in the
# properties below; this script sizes the passes, wires their textures and counts frames.
#
# The scene's nodes, in the order Godot 3 draws them (sibling viewports in tree order, before the
# viewport that holds them):
#   previous-<alias>  a copy of pass <alias>'s output of the previous frame (for feedback reads),
#                     taken before the passes run;
#   <alias>           one Viewport per pass, its TextureRect "Pass" carrying the pass's
#                     ShaderMaterial over the pass's main input;
#   history-<N>       the original of N frames ago (copied after the passes, oldest first);
#   crt-background, crt-display   the last pass at the screen's rectangle, over black.
# Pass viewports use render_target_v_flip so that every reader samples them upright.
#
# Use: instance the scene and set `source` to the picture, e.g. the ViewportTexture of the
# Viewport your game draws into (keep that Viewport before this scene in the tree, so it is drawn
# first). The scene fills its parent; resize it as any Control. `frame` counts frames (shaders
# get it as frameCount) and `seconds` the time since start (shaders get it reduced exactly, as
# hostTime); set `playing = false` to drive both yourself.
extends Control

export(Texture) var source = null setget set_source
export var playing = true
export var frame = 0 setget set_frame
export var seconds = 0.0 setget set_seconds  # a 64-bit float: exact enough for years

# The pipeline (written by crtforge).
export var pixel_aspect = Vector2(1, 1)
export var screen_aspect = Vector2(0, 0)  # (0, 0): the source's display aspect
export var fit = "stretch"  # stretch | aspect | integer
export var passes = []  # per pass: alias, scale, hdr, input, textures, frame_count_mod, frame_count, sizes
export var feedback = []  # aliases of passes read as the previous frame
export var history = 0  # frames of the original kept
export var luts = {}  # name -> {path, filter, wrap}

var _lut_textures = {}
var _placeholder = null
var _flagged = {}


func _ready():
	# The pass shaders read dFdx (the node's size in pixels); GLES2 rejects them and Godot would then
	# show the raw picture with only a shader compile message. Say what is wrong instead.
	if OS.get_current_video_driver() == OS.VIDEO_DRIVER_GLES2:
		push_error("crtforge: %s needs the GLES3 renderer (Project Settings > Rendering > Quality > Driver); its shaders read dFdx, which GLES2 lacks" % name)
	_load_luts()
	_wire()
	_layout()
	connect("resized", self, "_layout")
	_apply_frame()


func _process(delta):
	_apply_frame()
	if playing:
		frame += 1
		seconds += delta


func set_source(texture):
	source = texture
	if is_inside_tree():
		_wire()
		_layout()


func set_frame(value):
	frame = value
	if is_inside_tree():
		_apply_frame()


func set_seconds(value):
	seconds = value
	if is_inside_tree():
		_apply_frame()


# The texture the original comes from: `source`, or black until one is set.
func _original():
	if source != null:
		return source
	if _placeholder == null:
		var image = Image.new()
		image.create(1, 1, false, Image.FORMAT_RGBA8)
		image.fill(Color(0, 0, 0, 1))
		_placeholder = ImageTexture.new()
		_placeholder.create_from_image(image, 0)
	return _placeholder


# A LUT from its PNG (the imported texture's image when the editor has imported it, what an
# exported game has; else the file read directly), as a float texture: Godot 3 decodes 8-bit
# textures as sRGB when a float viewport draws them, and a LUT's texels must arrive as stored.
func _load_luts():
	for name in luts.keys():
		var path = luts[name]["path"]
		var image = null
		if ResourceLoader.exists(path):
			var imported = load(path)
			if imported != null:
				image = imported.get_data()
		if image == null:
			image = Image.new()
			if image.load(path) != OK:
				push_error("crtforge: cannot load LUT '%s' from %s" % [name, path])
				continue
		image.convert(Image.FORMAT_RGBAF)
		var flags = 0
		if luts[name].get("mipmap", false):
			# Read through a mip chain: uploaded with its levels (a texture created without the flag
			# keeps level 0 only); _flags keeps FLAG_MIPMAPS.
			image.generate_mipmaps()
			flags = Texture.FLAG_MIPMAPS
		var texture = ImageTexture.new()
		texture.create_from_image(image, flags)
		_lut_textures[name] = texture


# Godot 3 filters and wraps per texture, not per read: the first reader (in pass order) sets them.
# Readers that disagree are listed in the scene's README notes.
func _flags(texture, spec):
	if texture == null or _flagged.has(texture):
		return
	_flagged[texture] = true
	var flags = 0
	if spec.get("filter", "linear") == "linear":
		flags |= Texture.FLAG_FILTER
	if spec.get("mipmap", false) and texture is ImageTexture:  # a LUT; viewports have no mip chain
		flags |= Texture.FLAG_MIPMAPS
	var wrap = spec.get("wrap", "clamp_to_edge")
	if wrap == "repeat":
		flags |= Texture.FLAG_REPEAT
	elif wrap == "mirrored_repeat":
		flags |= Texture.FLAG_MIRRORED_REPEAT
	texture.flags = flags


func _texture(spec):
	var texture = null
	match spec["from"]:
		"original":
			var back = int(spec.get("frames_back", 0))
			texture = _original() if back == 0 else get_node("history-%d" % back).get_texture()
		"pass":
			texture = get_node(spec["name"]).get_texture()
		"feedback":
			texture = get_node("previous-" + spec["name"]).get_texture()
		"lut":
			texture = _lut_textures.get(spec["name"])
	_flags(texture, spec)
	return texture


func _wire():
	_flagged.clear()
	for p in passes:
		var rect = get_node(p["alias"] + "/Pass")
		rect.texture = _texture(p["input"])
		for name in p["textures"].keys():
			rect.material.set_shader_param(name, _texture(p["textures"][name]))
	for alias in feedback:
		var copy = get_node("previous-" + alias + "/Copy")
		copy.texture = get_node(alias).get_texture()
		_flags(copy.texture, {"filter": "nearest"})
	for n in range(1, history + 1):
		var copy = get_node("history-%d/Copy" % n)
		copy.texture = _original() if n == 1 else get_node("history-%d" % (n - 1)).get_texture()
		_flags(copy.texture, {"filter": "nearest"})
	var display = get_node("crt-display")
	display.texture = get_node(passes[passes.size() - 1]["alias"]).get_texture()
	_flags(display.texture, {"filter": "nearest"})


func _apply_frame():
	for p in passes:
		var material = get_node(p["alias"] + "/Pass").material
		if p["frame_count"]:
			var mod = int(p["frame_count_mod"])
			material.set_shader_param("frameCount", frame % mod if mod > 0 else frame)
		if p.has("time_speed"):
			material.set_shader_param("hostTime", _reduced_time(material, p["time_speed"]))


# `seconds` reduced by one period of the pass's angular speed (a uniform's name or a number) in
# double precision, so the shader's phase time * speed is exact at any hour: what crtforge's
# other hosts give their shaders as time (crtforge::shader_time()).
func _reduced_time(material, speed):
	if typeof(speed) == TYPE_STRING:
		speed = material.get_shader_param(speed)
	speed = abs(float(speed))
	if speed == 0.0:
		return seconds
	var phase = fmod(seconds * speed, TAU)
	if phase < 0.0:
		phase += TAU
	return phase / speed


# ---- geometry: the same rules as crtforge's scene model (generator/scene.cpp) ----

func _screen_aspect(source_size):
	if screen_aspect.x > 0:
		return screen_aspect.x / screen_aspect.y
	return source_size.x * pixel_aspect.x / (source_size.y * pixel_aspect.y)


func _centred(display, width, height):
	width = int(clamp(width, 1, display.x))
	height = int(clamp(height, 1, display.y))
	return Rect2((int(display.x) - width) / 2, (int(display.y) - height) / 2, width, height)


func _screen_rect(display, source_size):
	if fit == "stretch" or source_size.x <= 0 or source_size.y <= 0:
		return Rect2(Vector2(), display)
	var aspect = _screen_aspect(source_size)
	if fit == "integer":
		var k = int(display.y) / int(source_size.y)
		while k >= 1:
			var height = k * int(source_size.y)
			var width = int(round(height * aspect))
			if width <= display.x:
				return _centred(display, width, height)
			k -= 1
	if display.x >= display.y * aspect:
		return _centred(display, int(round(display.y * aspect)), display.y)
	return _centred(display, display.x, int(round(display.x / aspect)))


func _axis(type, factor, input, viewport):
	var base = 1.0
	if type == "source":
		base = input
	elif type == "viewport":
		base = viewport
	return int(clamp(round(base * factor), 1, 16384))


func _pass_sizes(source_size, screen):
	var sizes = {}
	var ordered = []
	for p in passes:
		var input = source_size
		var from = p["input"]
		if (from["from"] == "pass" or from["from"] == "feedback") and sizes.has(from["name"]):
			input = sizes[from["name"]]
		var s = p["scale"]
		var size = Vector2(_axis(s[0], float(s[1]), input.x, screen.x), _axis(s[2], float(s[3]), input.y, screen.y))
		sizes[p["alias"]] = size
		ordered.append(size)
	# The last pass draws the screen, whatever its scale says.
	ordered[ordered.size() - 1] = Vector2(max(screen.x, 1), max(screen.y, 1))
	return ordered


# Godot draws nothing into a viewport under 2 pixels: a pass 1 pixel wide or tall gets 2, both
# computing its one pixel (its shader holds that axis at the centre; readers are told 1).
func _resize(viewport, child, size):
	size = Vector2(max(size.x, 2), max(size.y, 2))
	viewport.size = size
	child.rect_position = Vector2()
	child.rect_size = size


func _layout():
	var display = Vector2(max(1, round(rect_size.x)), max(1, round(rect_size.y)))
	var source_size = _original().get_size()
	var screen = _screen_rect(display, source_size)
	var sizes = _pass_sizes(source_size, screen.size)
	for i in range(passes.size()):
		var viewport = get_node(passes[i]["alias"])
		_resize(viewport, viewport.get_node("Pass"), sizes[i])
		if passes[i].get("sizes", false):  # a program pass: its vertex stage has no other way to know them
			var material = viewport.get_node("Pass").material
			material.set_shader_param("outputSize", sizes[i])
			material.set_shader_param("viewportSize", screen.size)
	for alias in feedback:
		var copy = get_node("previous-" + alias)
		_resize(copy, copy.get_node("Copy"), get_node(alias).size)
	for n in range(1, history + 1):
		var copy = get_node("history-%d" % n)
		_resize(copy, copy.get_node("Copy"), source_size)
	var background = get_node("crt-background")
	background.rect_position = Vector2()
	background.rect_size = display
	var shown = get_node("crt-display")
	shown.rect_position = screen.position
	shown.rect_size = screen.size
