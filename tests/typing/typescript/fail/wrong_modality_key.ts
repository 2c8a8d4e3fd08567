// A camera's images are keyed by modality: a wrong key is refused, with the right one suggested.
import type { UCameraSensorComponent } from "../../../../generated/engine/ts/api.gen.js";

export async function depthOf(camera: UCameraSensorComponent): Promise<unknown> {
  const pixels = await camera.read_pixels();
  return pixels.final_colour;  // T: TS2551: Property 'final_colour' does not exist on type 'FCameraPixels'. Did you mean 'final_color'?
}
