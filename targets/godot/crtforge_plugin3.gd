tool
extends EditorPlugin
# crtforge's editor plugin (Godot 3): enable it in Project Settings > Plugins, then add a
# "CrtOverlay" node (Add Node dialog) to any scene and pick its preset in the inspector. The
# preset list is every <preset>.screen.tres in this folder: what `crtforge export` wrote here.


func _enter_tree():
	add_custom_type("CrtOverlay", "CanvasLayer", preload("crtforge_overlay.gd"), null)
	print("crtforge: CrtOverlay node type added (%d presets)" % preload("crtforge_overlay.gd").presets().size())


func _exit_tree():
	remove_custom_type("CrtOverlay")
