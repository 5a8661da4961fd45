// Types of crtforge-presets/babylon. Babylon.js itself is not a dependency: the pass uses the
// engine's GPUDevice and textures through the members below.
/// <reference types="@webgpu/types" />
import type { CrtParam, CrtScene, ParamValue } from './index.js';

/** What the pass uses of a Babylon.js WebGPUEngine (after `await engine.initAsync()`). */
export interface BabylonWebGPUEngineLike {
  flushFramebuffer(): void;
}

/** A Babylon texture (BaseTexture, RenderTargetTexture) or its InternalTexture. */
export type BabylonTextureLike = { getInternalTexture(): unknown } | object;

export interface BabylonCrtPass {
  readonly scene: CrtScene;
  params(): Array<CrtParam & { pass: string }>;
  setParam(name: string, value: ParamValue): void;
  /** Draws `input` through the preset into `output`, at output's size; submits on the engine's device. */
  render(input: BabylonTextureLike, output: BabylonTextureLike,
         options?: { frame?: number; time?: number; fit?: 'stretch' | 'aspect' | 'integer' }): Promise<void>;
  /** Records the pass into your encoder, onto a view of the format the pass was made for. */
  encode(encoder: GPUCommandEncoder, options: Parameters<CrtScene['encode']>[1]): void;
  /** The GPUTexture Babylon made for a texture. */
  textureOf(texture: BabylonTextureLike): GPUTexture;
  destroy(): void;
}

export function createBabylonCrtPass(engine: BabylonWebGPUEngineLike, name: string,
                                     options?: { format?: GPUTextureFormat }): Promise<BabylonCrtPass>;
