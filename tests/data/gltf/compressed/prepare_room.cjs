// The room input of make_variants.sh: the generated room without its textures, so that
// each variant is one self-contained .glb. Usage: node prepare_room.cjs IN OUT
const { NodeIO } = require('@gltf-transform/core');
const { ALL_EXTENSIONS } = require('@gltf-transform/extensions');

async function main([input, output]) {
  const io = new NodeIO().registerExtensions(ALL_EXTENSIONS);
  const doc = await io.read(input);
  for (const texture of doc.getRoot().listTextures()) texture.dispose();
  await io.write(output, doc);
}

main(process.argv.slice(2)).catch((e) => { console.error(e); process.exit(1); });
