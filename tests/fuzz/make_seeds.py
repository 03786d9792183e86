#!/usr/bin/python3
"""Writes the fuzz targets' seed corpora (corpus/<target>/): small valid inputs of every form each
parser takes, from which libFuzzer mutates. Run again after changing it; its output is committed.
Model seeds are small files of Debian's assimp-testmodels, each prefixed with fuzz_model's
selector byte (the index of its extension in fuzz_model.cpp's kExtensions)."""
import os, random, re, struct, sys

HERE = os.path.dirname(os.path.abspath(__file__))
rng = random.Random(36)

def out(target, name, data):
    d = os.path.join(HERE, 'corpus', target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), 'wb') as f:
        f.write(data if isinstance(data, bytes) else data.encode())

def chain(w, h, block_bytes, levels=None):
    """Random bytes of each level of a full chain (block_bytes per 4x4 block; 0: RGBA8)."""
    out_levels = []
    while True:
        if block_bytes:
            n = ((w + 3) // 4) * ((h + 3) // 4) * block_bytes
        else:
            n = w * h * 4
        out_levels.append(bytes(rng.getrandbits(8) for _ in range(n)))
        if (w == 1 and h == 1) or (levels and len(out_levels) == levels):
            return out_levels
        w, h = max(1, w // 2), max(1, h // 2)

def bc7(levels):  # a valid mode bit in each block
    fixed = []
    for l in levels:
        b = bytearray(l)
        for i in range(0, len(b), 16):
            m = (i // 16) % 8
            b[i] = ((b[i] << (m + 1)) | (1 << m)) & 0xFF
        fixed.append(bytes(b))
    return fixed

def dds(fourcc, dxgi, w, h, images, caps2=0, misc=0, array=1):
    head = [124, 0x1 | 0x2 | 0x4 | 0x1000 | 0x20000, h, w, 0, 0, len(images[0])] + [0] * 11 + \
           [32, 0x4, 0, 0, 0, 0, 0, 0, 0x1000 | 0x400000 | 0x8, caps2, 0, 0, 0]
    b = bytearray(b'DDS ' + struct.pack('<31I', *head))
    b[84:88] = fourcc
    if fourcc == b'DX10':
        b += struct.pack('<5I', dxgi, 3, misc, array, 0)
    for image in images:
        for l in image:
            b += l
    return bytes(b)

KTX1 = bytes([0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31, 0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A])
KTX2 = bytes([0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A])

def ktx1(internal, w, h, images, elements=0, faces=1):
    rgba8 = internal in (0x8058, 0x8C43)
    b = bytearray(KTX1 + struct.pack('<13I', 0x04030201, 0x1401 if rgba8 else 0, 1, 0x1908 if rgba8 else 0,
                                     internal, 0x1908, w, h, 0, elements, faces, len(images[0]), 0))
    lone_cube = faces == 6 and elements == 0
    for k in range(len(images[0])):
        b += struct.pack('<I', len(images[0][k]) * (1 if lone_cube else len(images)))
        for image in images:
            b += image[k]
            while lone_cube and len(b) % 4:
                b.append(0)
        while len(b) % 4:
            b.append(0)
    return bytes(b)

def ktx2(vk, w, h, images, layers=0, faces=1):
    count = len(images[0])
    b = bytearray(KTX2 + struct.pack('<9I', vk, 1, w, h, 0, layers, faces, count, 0))
    b += struct.pack('<4I2Q', 0, 0, 0, 0, 0, 0)
    sizes = [sum(len(im[k]) for im in images) for k in range(count)]
    at = len(b) + 24 * count
    offsets = [0] * count
    for k in reversed(range(count)):
        offsets[k] = at
        at += sizes[k]
    for k in range(count):
        b += struct.pack('<3Q', offsets[k], sizes[k], sizes[k])
    for k in reversed(range(count)):
        for im in images:
            b += im[k]
    return bytes(b)

# texture_file: every container, 2D, arrays, cube maps, RGBA8 and block formats (full chains: a
# one-level block file would be encoded again on every run)
out('texture_file', 'dds_bc1_8x8', dds(b'DXT1', 0, 8, 8, [chain(8, 8, 8)]))
out('texture_file', 'dds_bc3_8x4', dds(b'DXT5', 0, 8, 4, [chain(8, 4, 16)]))
out('texture_file', 'dds_dx10_rgba8_array', dds(b'DX10', 28, 4, 4, [chain(4, 4, 0) for _ in range(2)], array=2))
out('texture_file', 'dds_dx10_bc7_srgb', dds(b'DX10', 99, 8, 8, [bc7(chain(8, 8, 16))]))
out('texture_file', 'dds_cube_bc1', dds(b'DXT1', 0, 4, 4, [chain(4, 4, 8) for _ in range(6)], caps2=0x200 | 0xFC00))
out('texture_file', 'dds_dx10_cube_array', dds(b'DX10', 71, 4, 4, [chain(4, 4, 8) for _ in range(12)], misc=4, array=2))
out('texture_file', 'ktx1_rgba8_4x2', ktx1(0x8058, 4, 2, [chain(4, 2, 0)]))
out('texture_file', 'ktx1_bc4_array', ktx1(0x8DBB, 8, 8, [chain(8, 8, 8) for _ in range(3)], elements=3))
out('texture_file', 'ktx1_srgb_cube', ktx1(0x8C43, 2, 2, [chain(2, 2, 0) for _ in range(6)], faces=6))
out('texture_file', 'ktx2_bc5_8x8', ktx2(141, 8, 8, [chain(8, 8, 16)]))
out('texture_file', 'ktx2_rgba8_cube_array', ktx2(37, 2, 2, [chain(2, 2, 0) for _ in range(12)], layers=2, faces=6))
out('texture_file', 'ktx2_bc2_array', ktx2(135, 4, 8, [chain(4, 8, 16) for _ in range(2)], layers=2))
out('texture_file', 'ktx1_etc2_rgba', ktx1(0x9278, 8, 8, [chain(8, 8, 16)]))
out('texture_file', 'ktx2_etc2_rgb_srgb', ktx2(148, 8, 4, [chain(8, 4, 8)]))
out('texture_file', 'ktx2_etc2_a1_array', ktx2(149, 4, 4, [chain(4, 4, 8) for _ in range(2)], layers=2))

# query_trace: every header form, with comments, a byte-order mark, CRLF, spaces
out('query_trace', 'lod', '# a comment\nu,v,lod\n0.5,0.5,0\n0.25, 0.75, 1.5\n\n-3,1e3,-2\n' +
    ''.join('%g,%g,%g\n' % (rng.random(), rng.random() * 2 - 0.5, rng.random() * 8 - 2) for _ in range(12)))
out('query_trace', 'deriv_bias', 'tex,smp,u,v,dudx,dvdx,dudy,dvdy,bias\r\n0,1,0.5,0.5,0.01,0,0,0.01,-1\r\n3,0,0.1,0.9,1,2,3,4,0.5\r\n' +
    ''.join('%d,%d,%g,%g,%g,0,0,%g,%g\r\n' % (i % 16, i % 3, rng.random(), rng.random(), rng.random() / 64, rng.random() / 64, i / 4 - 1) for i in range(10)))
out('query_trace', 'frame', 'tex,u,v,dudx,dvdx,dudy,dvdy,quad,x,y,helper\n'
    '0,0.5,0.5,0.01,0,0,0.01,0,0,0,0\n0,0.51,0.5,0.01,0,0,0.01,0,1,0,1\n1,0.5,0.5,0.01,0,0,0.01,1,2,0,0\n')
out('query_trace', 'fetch_layer', '\ufefftex,i,j,layer,level\n0,3,4,1,0\n1,-1,70000,2,3\n')
out('query_trace', 'gather', 'tex,smp,u,v\n0,0,0.5,0.5\n')
out('query_trace', 'compare', 'u,v,layer,ref,lod\n0.5,0.5,1,0.25,0\n')
out('query_trace', 'cube', 'x,y,z,dxdx,dydx,dzdx,dxdy,dydy,dzdy\n1,0.2,-0.3,0.01,0,0,0,0.01,0\n-0.5,-1,0.5,0,0,0,0,0,0\n')
out('query_trace', 'cube_lod', 'tex,x,y,z,layer,ref,lod\n0,0,0,1,2,0.5,1\n')

# texture_list: every field
out('texture_list', 'fields', '# id path fields\n0 checker repeat clamp min=linear mag=nearest mip=linear\n'
    '1 testcard:64x32 mirror srgb base=1 max=3\n2 gradient border border=opaque-white reduction=min\n'
    '3 checker clamp depth compare=less-or-equal\n4 checker unnormalized\n')
out('texture_list', 'gl_names', '0 checker GL_CLAMP_TO_EDGE min=GL_LINEAR_MIPMAP_NEAREST\n')

# scene_file and camera_path
out('scene_file', 'models', '{"models": [{"file": "a.obj", "translation": [1, 2, 3], "rotation": [0, 90, 0], '
    '"scale": 2, "sampler": {"wrap": "clamp", "min_filter": "GL_LINEAR_MIPMAP_LINEAR", "mag_filter": "nearest", '
    '"mipmap_mode": "none", "border_color": "opaque-white"}}, {"file": "/b/c.gltf"}]}')
out('scene_file', 'wraps', '{"models": [{"file": "m.dae", "sampler": {"wrap_u": "repeat", "wrap_v": "mirror"}}]}')
out('camera_path', 'keys', '{"keyframes": [{"eye": [0, 1, 5], "target": [0, 0, 0], "fovy": 45}, '
    '{"eye": [5, 1, 0], "target": [0, 0.5, 0]}]}')
out('camera_path', 'one', '{"keyframes": [{"eye": [1e3, -2, 0.5], "target": [0, 0, 0]}]}')

# model: small files of assimp-testmodels, each format fuzz_model takes
src = open(os.path.join(HERE, 'fuzz_model.cpp')).read()
exts = re.findall(r'"(\w+)"', src[src.index('kExtensions[]'):src.index('kFormats =')])
models = '/usr/share/assimp/models'
taken = {}
for root, _, files in sorted(os.walk(models)):
    for f in sorted(files):
        ext = f.rsplit('.', 1)[-1].lower()
        p = os.path.join(root, f)
        if ext in exts and os.path.getsize(p) <= 6000 and taken.get(ext, 0) < 3 and 'invalid' not in root:
            taken[ext] = taken.get(ext, 0) + 1
            data = open(p, 'rb').read()
            out('model', ext + '_' + f.replace('.', '_'), bytes([exts.index(ext)]) + data)
            if taken[ext] == 1:  # loaded as a mirror (render --envmap): the selector's top bit
                out('model', 'mirror_' + ext + '_' + f.replace('.', '_'), bytes([128 + exts.index(ext)]) + data)
# ASTC (at the end: the seeds above keep their bytes): astcenc's .astc file and a KTX2 of 5x5 blocks.
def astc_level(w, h, fw, fh):
    return bytes(rng.getrandbits(8) for _ in range(((w + fw - 1) // fw) * ((h + fh - 1) // fh) * 16))
out('texture_file', 'astc_6x6_10x6.astc', bytes([0x13, 0xAB, 0xA1, 0x5C, 6, 6, 1, 10, 0, 0, 6, 0, 0, 1, 0, 0]) +
    astc_level(10, 6, 6, 6))
out('texture_file', 'ktx2_astc_5x5_srgb', ktx2(162, 8, 8, [[astc_level(8, 8, 5, 5), astc_level(4, 4, 5, 5),
                                                             astc_level(2, 2, 5, 5), astc_level(1, 1, 5, 5)]]))
# EAC R11 / RG11 (after ASTC, for the same reason): KTX 1 unsigned R11, KTX2 signed RG11.
out('texture_file', 'ktx1_eac_r11', ktx1(0x9270, 8, 4, [chain(8, 4, 8)]))
out('texture_file', 'ktx2_eac_rg11_snorm', ktx2(156, 4, 8, [chain(4, 8, 16)]))

print('seeds:', {t: len(os.listdir(os.path.join(HERE, 'corpus', t))) for t in sorted(os.listdir(os.path.join(HERE, 'corpus')))})
print('model formats without a seed:', [e for e in exts if e not in taken])

