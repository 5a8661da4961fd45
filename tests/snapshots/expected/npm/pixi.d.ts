// Types of crtforge-presets/pixi. PixiJS itself is not a dependency: the pass uses the renderer's
// GPUDevice and texture system through the members below.
/// <reference types="@webgpu/types" />
import type { FrameworkCrtPass } from './index.js';

/** What the pass uses of a PixiJS v8 WebGPURenderer (after `await renderer.init()`). */
export interface PixiWebGPURendererLike {
  gpu: { device: GPUDevice };
  texture: { getGpuSource(source: object): GPUTexture };
}

/** A Pixi Texture (a RenderTexture) or its TextureSource. */
export type PixiTextureLike = { source: object } | object;

export type PixiCrtPass = FrameworkCrtPass<PixiTextureLike>;

export function createPixiCrtPass(renderer: PixiWebGPURendererLike, name: string,
                                  options?: { format?: GPUTextureFormat }): Promise<PixiCrtPass>;
