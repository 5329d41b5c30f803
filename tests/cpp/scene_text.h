// tests/cpp/scene_text.h - a scene given as pbrt-v4 text, loaded through a temporary file (the tests'
// scenes written inline); an unexpected refusal is a failed check (../c/check.h).
#ifndef UDM1_TEST_SCENE_TEXT_H
#define UDM1_TEST_SCENE_TEXT_H

#include "../c/check.h"
#include "scene.h"

#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

inline udm1scene::Scene load_scene_text(const std::string &text)
{
    char dir[] = "/tmp/udm1_test_scene_XXXXXX";
    if (!mkdtemp(dir)) return udm1scene::Scene();
    std::string path = std::string(dir) + "/s.pbrt";
    std::ofstream(path) << text;
    udm1scene::Scene s;
    try {
        s = udm1scene::load_scene(path);
    } catch (const udm1scene::SceneError &e) {
        std::fprintf(stderr, "unexpected scene error: %s\n", e.what());
        ++check_failures;
    }
    std::remove(path.c_str());
    rmdir(dir);
    return s;
}

#endif
