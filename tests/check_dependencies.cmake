# Fails when an include crosses the dependency rules of STYLE.md:
#   core/ includes no Qt and nothing from widgets/ or app/; widgets/ includes nothing from app/;
#   inside core, the lower modules do not include the higher ones (docs/architecture.md):
#   common ← soil, wheel ← contact ← compaction ← field; io ← identification, dynamics, gsa ←
#   scenario ← analysis ← project.
function(check_dir dir pattern message)
  file(GLOB_RECURSE files "${SOURCE_DIR}/${dir}/*.h" "${SOURCE_DIR}/${dir}/*.cpp")
  foreach(file IN LISTS files)
    file(STRINGS "${file}" hits REGEX "${pattern}")
    if(hits)
      message(SEND_ERROR "${file}: ${message}: ${hits}")
    endif()
  endforeach()
endfunction()

check_dir(core "#include *[<\"](Q[A-Za-z]|qcustomplot)" "core must stay Qt-free")
check_dir(core "#include *\"(widgets|app)/" "core must not include widgets/ or app/")
check_dir(widgets "#include *\"app/" "widgets must not include app/")
check_dir(core/common "#include *\"core/(soil|wheel|contact|compaction|field|analysis|identification|dynamics|scenario|io|project)/"
          "core/common is the bottom layer")
check_dir(core/soil "#include *\"core/(wheel|contact|analysis|identification|dynamics|scenario|io|project)/"
          "core/soil depends only on common")
check_dir(core/wheel "#include *\"core/(soil|contact|analysis|identification|dynamics|scenario|io|project)/"
          "core/wheel depends only on common")
check_dir(core/contact "#include *\"core/(analysis|identification|dynamics|scenario|io|project)/"
          "core/contact must not include higher modules")
check_dir(core/compaction "#include *\"core/(analysis|identification|dynamics|scenario|io|project|gsa)/"
          "core/compaction depends on contact, soil, wheel and common only")
check_dir(core/field "#include *\"core/(analysis|identification|dynamics|scenario|io|project|gsa)/"
          "core/field depends on compaction, contact, soil, wheel and common only")
check_dir(core/gsa "#include *\"core/(analysis|identification|dynamics|scenario|io|project)/"
          "core/gsa depends on compaction, contact, soil, wheel and common only")
check_dir(core/identification "#include *\"core/(analysis|dynamics|scenario|project)/"
          "core/identification depends on contact, io and common only")
check_dir(core/io "#include *\"core/(contact|analysis|identification|dynamics|scenario|project)/"
          "core/io reads the soil and wheel structs only")
check_dir(core/dynamics "#include *\"core/(analysis|identification|scenario|io|project)/"
          "core/dynamics depends on contact, soil, wheel and common only")
check_dir(core/scenario "#include *\"core/(analysis|project)/"
          "core/scenario must not include the analysis services or the project")
check_dir(core/analysis "#include *\"core/project/"
          "core/analysis must not include the project (the project holds analysis settings)")
check_dir(python "#include *[<\"](Q[A-Za-z]|qcustomplot|widgets/|app/)"
          "the Python module binds the core only (no Qt, widgets or app)")
