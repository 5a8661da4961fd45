@tool
extends CanvasLayer
# A CRT overlay node (Godot 4): post-processes everything drawn below it with a crtforge preset's
# screen shader. A full-rect ColorRect on layer 100 holds the preset's screen material; its mouse
# filter is Ignore, so the GUI below still gets every click. `preset` lists every
# <preset>.screen.tres of this folder (single-pass presets; whole scenes: use <preset>.tscn).

const FOLDER := "res://addons/crtforge/"

@export var preset: String = "":
	set(value):
		preset = value
		if is_inside_tree():
			_apply()

var _screen: ColorRect = null


static func presets() -> PackedStringArray:
	var names := PackedStringArray()
	var dir := DirAccess.open(FOLDER)
	if dir == null:
		return names
	for file in dir.get_files():
		# An exported game may list the material as <name>.screen.tres.remap.
		if file.ends_with(".screen.tres") or file.ends_with(".screen.tres.remap"):
			var preset_name := file.trim_suffix(".remap").trim_suffix(".screen.tres")
			if not names.has(preset_name):
				names.append(preset_name)
	names.sort()
	return names


func _init() -> void:
	layer = 100


func _ready() -> void:
	if preset == "":
		var all := presets()
		if all.size() > 0:
			preset = all[0]
	_apply()


# The material of `preset` on the full-rect ColorRect (made on first use).
func _apply() -> void:
	if _screen == null:
		_screen = ColorRect.new()
		_screen.name = "Screen"
		_screen.set_anchors_preset(Control.PRESET_FULL_RECT)
		_screen.mouse_filter = Control.MOUSE_FILTER_IGNORE
		add_child(_screen)
	var path := FOLDER + preset + ".screen.tres"
	if preset == "" or not ResourceLoader.exists(path):
		push_error("crtforge: no preset '%s' here (%s missing); have: %s" % [preset, path, ", ".join(presets())])
		_screen.material = null
		_screen.visible = false
		return
	_screen.material = load(path)
	_screen.visible = true


func _validate_property(property: Dictionary) -> void:
	if property.name == "preset":
		property.hint = PROPERTY_HINT_ENUM
		property.hint_string = ",".join(presets())
