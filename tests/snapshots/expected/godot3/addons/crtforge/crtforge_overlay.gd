tool
extends CanvasLayer
# A CRT overlay node (Godot 3): post-processes everything drawn below it with a crtforge preset's
# screen shader. A full-rect ColorRect on layer 100 holds the preset's screen material; its mouse
# filter is Ignore, so the GUI below still gets every click. `preset` lists every
# <preset>.screen.tres of this folder (single-pass presets; whole scenes: use <preset>.tscn).
# Needs the GLES3 renderer, like the shaders.

const FOLDER = "res://addons/crtforge/"

var preset = "" setget set_preset
var _screen = null


static func presets():
	var names = []
	var dir = Directory.new()
	if dir.open(FOLDER) != OK:
		return names
	dir.list_dir_begin(true, true)
	var file = dir.get_next()
	while file != "":
		# An exported game may list the material as <name>.screen.tres.remap.
		if file.ends_with(".screen.tres") or file.ends_with(".screen.tres.remap"):
			var preset_name = file.trim_suffix(".remap").trim_suffix(".screen.tres")
			if not names.has(preset_name):
				names.append(preset_name)
		file = dir.get_next()
	dir.list_dir_end()
	names.sort()
	return names


func _init():
	layer = 100


func _ready():
	if preset == "":
		var all = presets()
		if all.size() > 0:
			preset = all[0]
	_apply()


func set_preset(value):
	preset = value
	if is_inside_tree():
		_apply()


# The material of `preset` on the full-rect ColorRect (made on first use).
func _apply():
	if _screen == null:
		_screen = ColorRect.new()
		_screen.name = "Screen"
		_screen.anchor_right = 1.0
		_screen.anchor_bottom = 1.0
		_screen.mouse_filter = Control.MOUSE_FILTER_IGNORE
		add_child(_screen)
	var path = FOLDER + preset + ".screen.tres"
	if preset == "" or not ResourceLoader.exists(path):
		push_error("crtforge: no preset '%s' here (%s missing); have: %s" % [preset, path, PoolStringArray(presets()).join(", ")])
		_screen.material = null
		_screen.visible = false
		return
	_screen.material = load(path)
	_screen.visible = true


func _get_property_list():
	return [{"name": "preset", "type": TYPE_STRING, "hint": PROPERTY_HINT_ENUM,
		"hint_string": PoolStringArray(presets()).join(","), "usage": PROPERTY_USAGE_DEFAULT}]
