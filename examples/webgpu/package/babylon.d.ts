// Types of crtforge-presets/babylon. Babylon.js itself is not a dependency: the pass uses the
// engine's GPUDevice and textures through the members below.
/// <reference types="@webgpu/types" />
import type { FrameworkCrtPass } from './index.js';

/** What the pass uses of a Babylon.js WebGPUEngine (after `await engine.initAsync()`). */
export interface BabylonWebGPUEngineLike {
  flushFramebuffer(): void;
}

/** A Babylon texture (BaseTexture, RenderTargetTexture) or its InternalTexture. */
export type BabylonTextureLike = { getInternalTexture(): unknown } | object;

export type BabylonCrtPass = FrameworkCrtPass<BabylonTextureLike>;

export function createBabylonCrtPass(engine: BabylonWebGPUEngineLike, name: string,
                                     options?: { format?: GPUTextureFormat }): Promise<BabylonCrtPass>;
