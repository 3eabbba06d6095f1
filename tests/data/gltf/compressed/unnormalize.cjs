// A KHR_mesh_quantization variant with non-normalized integers: every normalized integer
// POSITION and TEXCOORD_n of IN keeps its stored values with normalized = false; the mesh's
// nodes get the scale 1 / (2^(n-1) - 1) (signed) or 1 / (2^n - 1) (unsigned) that the
// normalization applied, and textures using the texcoords a KHR_texture_transform scale that
// does the same. Usage: node unnormalize.cjs IN OUT
const { NodeIO } = require('@gltf-transform/core');
const { ALL_EXTENSIONS, KHRTextureTransform } = require('@gltf-transform/extensions');

const MAX = { Int8Array: 127, Uint8Array: 255, Int16Array: 32767, Uint16Array: 65535 };

function scaleOf(accessor) {
  return accessor.getNormalized() ? MAX[accessor.getArray().constructor.name] : undefined;
}

async function main([input, output]) {
  const io = new NodeIO().registerExtensions(ALL_EXTENSIONS);
  const doc = await io.read(input);
  const transforms = doc.createExtension(KHRTextureTransform);
  const done = new Set();
  for (const mesh of doc.getRoot().listMeshes()) {
    for (const prim of mesh.listPrimitives()) {
      const position = prim.getAttribute('POSITION');
      const positionScale = scaleOf(position);
      if (positionScale && !done.has(position)) {
        done.add(position);
        position.setNormalized(false);
        for (const node of mesh.listParents().filter((p) => p.propertyType === 'Node')) {
          const s = node.getScale();
          node.setScale(s.map((v) => v / positionScale));
        }
      }
      const uv = prim.getAttribute('TEXCOORD_0');
      const uvScale = uv && scaleOf(uv);
      if (!uvScale || done.has(uv)) continue;
      done.add(uv);
      uv.setNormalized(false);
      const material = prim.getMaterial();
      const info = material && material.getBaseColorTextureInfo();
      if (material && material.getBaseColorTexture() && info)
        info.setExtension('KHR_texture_transform', transforms.createTransform().setScale([1 / uvScale, 1 / uvScale]));
    }
  }
  if (doc.getRoot().listTextures().length > 0) transforms.setRequired(true);
  else transforms.dispose();
  await io.write(output, doc);
}

main(process.argv.slice(2)).catch((e) => { console.error(e); process.exit(1); });
