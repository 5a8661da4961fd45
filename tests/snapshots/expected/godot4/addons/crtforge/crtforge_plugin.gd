@tool
extends EditorPlugin
# crtforge's editor plugin (Godot 4): enable it in Project Settings > Plugins, then add a
# "CrtOverlay" node (Add Node dialog) to any scene and pick its preset in the inspector. The
# preset list is every <preset>.screen.tres in this folder: what `crtforge export` wrote here.


func _enter_tree() -> void:
	add_custom_type("CrtOverlay", "CanvasLayer", preload("crtforge_overlay.gd"), null)


func _exit_tree() -> void:
	remove_custom_type("CrtOverlay")
