// Types of crtforge-presets/pixi. PixiJS itself is not a dependency: the pass uses the renderer's
// GPUDevice and texture system through the members below.
/// <reference types="@webgpu/types" />
import type { CrtParam, CrtScene, ParamValue } from './index.js';

/** What the pass uses of a PixiJS v8 WebGPURenderer (after `await renderer.init()`). */
export interface PixiWebGPURendererLike {
  gpu: { device: GPUDevice };
  texture: { getGpuSource(source: object): GPUTexture };
}

/** A Pixi Texture (a RenderTexture) or its TextureSource. */
export type PixiTextureLike = { source: object } | object;

export interface PixiCrtPass {
  readonly scene: CrtScene;
  params(): Array<CrtParam & { pass: string }>;
  setParam(name: string, value: ParamValue): void;
  /** Draws `input` through the preset into `output`, at output's size; submits on the renderer's device. */
  render(input: PixiTextureLike, output: PixiTextureLike,
         options?: { frame?: number; time?: number; fit?: 'stretch' | 'aspect' | 'integer' }): Promise<void>;
  /** Records the pass into your encoder, onto a view of the format the pass was made for. */
  encode(encoder: GPUCommandEncoder, options: Parameters<CrtScene['encode']>[1]): void;
  /** The GPUTexture Pixi made for a texture. */
  textureOf(texture: PixiTextureLike): GPUTexture;
  destroy(): void;
}

export function createPixiCrtPass(renderer: PixiWebGPURendererLike, name: string,
                                  options?: { format?: GPUTextureFormat }): Promise<PixiCrtPass>;
