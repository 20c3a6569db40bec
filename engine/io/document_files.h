// A document's files: opening a scene file as a document, saving it, importing a mesh file
// into it. The document model (engine/document) holds no file I/O; this is where it meets the
// disk.
//
// Threads: the caller's (the editor's UI thread, tests); synchronous.
#pragma once

#include <string>
#include <vector>

#include "engine/document/document.h"

namespace strata {

// Loads a scene file (loadScene) as a clean document belonging to `path`; warnings, if any, are
// appended to `warnings`. A mesh file that cannot be read leaves its node without its mesh
// (MissingMeshes::Keep, said in a warning): the rest of the work opens. Throws strata::Error.
Document openDocument(const std::string& path, std::vector<std::string>* warnings = nullptr);

// Saves to document.path(); throws strata::Error when the document has none.
void saveDocument(Document& document);

// The stamp of the file at `path` now (its modification time and size; unknown where absent).
Document::FileStamp fileStampOf(const std::string& path);
// "" where the document's file is as it was when it was opened or saved here (or it has no file
// yet, or the file is gone: a save then overwrites nothing); else a sentence for the artist
// saying that it changed since, and how ("at 2026-11-30 23:11:05, 12345 bytes"). openDocument
// and saveDocumentAs stamp the document.
std::string changedOnDisk(const Document& document);
// Saves atomically (saveScene) to `path`, first copying an existing file there to
// "<path>.bak". Mesh paths are written relative to the file's folder where the mesh lies
// inside it, absolute otherwise. The document then belongs to `path` and is clean.
void saveDocumentAs(Document& document, const std::string& path);

// Reads a closed mesh file (readMeshFile) and adds it as a mesh leaf named after its file's
// stem, its path made absolute (see Document's constructor) with the file's content hash, onto
// `target` (0 = the root) with `mode` (Document::place) with `transform` (import options: unit
// scale, up axis); *sentence says what it does. With `acceptOpen` a mesh that is not a closed
// oriented surface is taken too, the leaf marked open (Node::meshOpen). One undo step. Returns
// the new leaf's id. Throws strata::Error.
NodeId importMeshFile(Document& document, const std::string& file, NodeId target = 0,
                      PlaceMode mode = PlaceMode::Add, const Transform& transform = Transform{},
                      std::string* sentence = nullptr, bool acceptOpen = false);

// A mesh leaf kept without its mesh because it is open (Node::meshRefusedAsOpen): its file read
// again and taken as an open mesh (Node::meshOpen, saved as "open": true). One undo step.
// Throws strata::Error (naming the file) where it cannot be read even so.
void acceptOpenMesh(Document& document, NodeId id);

}  // namespace strata
