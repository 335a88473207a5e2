// `ctmap serve`: the editing session of issue 15 over HTTP on localhost (cpp-httplib). The JSON
// API (README "ctmap serve") maps again on every change and answers with a certified map or the
// message `ctmap map` would give; the session keeps its last valid features and map.
#include <stdlib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "commands.h"
#include "ctmap/edit/edit_session.h"
#include "ctmap/errors.h"
#include "ctmap/io/features.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
// After Eigen (through the headers above): httplib.h includes <resolv.h>, whose `_res` macro
// breaks Eigen's headers if they come later.
#include <httplib.h>

namespace ctmap::cli {
namespace {

namespace fs = std::filesystem;

struct ServeArgs {
    std::string mesh, image, features, web, host = "127.0.0.1";
    bool open = false;
    bool full = false;  ///< --full: every move runs the whole pipeline
    int port = 8080;
    double snap = -1;
    std::string border = "auto";
    bool quiet = false;
};

std::atomic<bool> g_stop{false};
extern "C" void on_signal(int) { g_stop = true; }

/// A JSON answer with its status (text that is not UTF-8, as a raw byte of a request quoted in a
/// message, is replaced, never thrown on).
void reply(httplib::Response& res, int status, const nlohmann::json& body) {
    res.status = status;
    res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), "application/json");
}

/// A request body that is not the JSON expected (BadInput: HTTP 400 below).
class BadRequest : public BadInput {
public:
    explicit BadRequest(const std::string& problem) : BadInput("request", problem) {}
};

/// The request's JSON body. \throw BadRequest if it is not JSON.
nlohmann::json request_json(const httplib::Request& req) {
    try {
        return nlohmann::json::parse(req.body, nullptr, true, false);
    } catch (const nlohmann::json::exception& e) {
        throw BadRequest(std::string("the body is not JSON: ") + e.what());
    }
}

/// The JSON answer for the exception being handled (call from a catch block): a malformed request
/// -> 400, BadInput -> 422, anything else -> 500, with the CLI's exit code (2 or 3) in "exit_code".
void reply_current_error(httplib::Response& res) {
    try {
        throw;
    } catch (const BadRequest& e) {
        reply(res, 400, {{"error", e.what()}, {"exit_code", int(kExitBadInput)}});
    } catch (const BadInput& e) {
        reply(res, 422, {{"error", e.what()}, {"exit_code", int(kExitBadInput)}});
    } catch (const std::exception& e) {
        reply(res, 500, {{"error", e.what()}, {"exit_code", int(kExitInternal)}});
    } catch (...) {
        reply(res, 500, {{"error", "an unknown failure"}, {"exit_code", int(kExitInternal)}});
    }
}

/// Runs `f` on the session under the lock and answers its JSON, or the error (reply_current_error).
/// The server never stops on an error.
template <class F>
void guarded(std::mutex& m, httplib::Response& res, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
        std::lock_guard<std::mutex> lock(m);
        reply(res, 200, f());
    } catch (...) {
        reply_current_error(res);
    }
    // The server's time for the request: the wait for the session, the work, and the JSON answer
    // built and serialised (the socket write comes after; the standard header that browsers'
    // developer tools show; bench/serve_latency.py reads it).
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    res.set_header("Server-Timing", "handler;dur=" + std::to_string(ms));
}

/// Writes the session's map with `write` into a private scratch folder and returns file `name`'s bytes.
template <class W>
std::string map_file_bytes(const std::string& name, W&& write) {
    std::string tmpl = (fs::temp_directory_path() / "ctmap_serve_XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw InternalError("cannot make a scratch folder in " + fs::temp_directory_path().string());
    const fs::path dir(tmpl);
    std::string bytes;
    try {
        write(dir);
        std::ifstream in(dir / name, std::ios::binary);
        std::ostringstream os;
        os << in.rdbuf();
        bytes = os.str();
    } catch (...) {
        std::error_code ec;
        fs::remove_all(dir, ec);
        throw;
    }
    std::error_code ec;
    fs::remove_all(dir, ec);
    return bytes;
}

/// The editor page's folder (index.html, editor.js, three/ from npm): --web, else `web` beside the
/// program (the build tree), else `../share/ctmap/web` (an installed program). Empty if none.
std::string find_web_root(const std::string& given) {
    auto holds_page = [](const fs::path& d) { return fs::is_regular_file(d / "index.html") && fs::is_regular_file(d / "editor.js"); };
    if (!given.empty()) {
        if (!holds_page(given)) throw BadInput(given, "--web: no index.html and editor.js in this folder");
        return given;
    }
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return "";
    for (const fs::path& d : {exe.parent_path() / "web", exe.parent_path().parent_path() / "share" / "ctmap" / "web"})
        if (holds_page(d)) return d.string();
    return "";
}

int run_serve(const ServeArgs& a) {
    if (a.host.empty() || a.host.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789.:-") !=
                              std::string::npos)
        throw BadInput(a.host, "--host must be a host name or an IP address");
    const std::string web = find_web_root(a.web);
    const TriMesh mesh = read_mesh(a.mesh);
    require_disc(compute_topology(mesh), a.mesh, NotDiscAdvice::cut_open);
    const Image img = read_image(a.image);
    std::optional<FeatureSet> initial;
    std::string features_path = a.features;
    if (!a.features.empty() && fs::exists(a.features)) {
        read_input_file(a.features, "features file");  // a regular file within the size limit
        initial = read_features(a.features);
        if (initial->units == "pixels" && initial->image_size &&
            ((*initial->image_size)[0] != img.width || (*initial->image_size)[1] != img.height))
            throw BadInput(a.features, "\"image_size\" [" + std::to_string((*initial->image_size)[0]) + ", " +
                                           std::to_string((*initial->image_size)[1]) + "] differs from the size of " +
                                           a.image + " (" + std::to_string(img.width) + " x " +
                                           std::to_string(img.height) + ")");
    } else if (!a.features.empty()) {
        // A new file: it will be created by the first save; its folder must exist now.
        const fs::path parent = fs::absolute(a.features).parent_path();
        if (!fs::is_directory(parent)) throw BadInput(a.features, "its folder does not exist");
    }
    EditSessionOptions opt;
    opt.map.snap = a.snap;
    opt.map.auto_border = a.border == "auto";
    opt.incremental = !a.full;
    EditSession session(mesh, a.mesh, a.image, img.width, img.height, features_path, initial, opt);
    std::mutex m;

    httplib::Server svr;
    std::atomic<int> svr_port{-1};  // known once bound; requests come only after that
    svr.set_payload_max_length(64u << 20);
    // SO_REUSEADDR only: httplib's default adds SO_REUSEPORT, with which a second server on a port
    // in use starts too and the two share the requests.
    svr.set_socket_options([](socket_t sock) {
        int yes = 1;
        setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    });
    svr.Get("/api/state", [&](const httplib::Request&, httplib::Response& res) {
        guarded(m, res, [&] { return session.state(); });
    });
    svr.Put("/api/features", [&](const httplib::Request& req, httplib::Response& res) {
        guarded(m, res, [&] { return session.set_features(req.body); });
    });
    svr.Post("/api/move", [&](const httplib::Request& req, httplib::Response& res) {
        guarded(m, res, [&] {
            const nlohmann::json j = request_json(req);
            if (!j.is_object() || !j.contains("name") || !j["name"].is_string() || !j.contains("image") ||
                !j["image"].is_array() || j["image"].size() != 2 || !j["image"][0].is_number() || !j["image"][1].is_number())
                throw BadRequest("a move is {\"name\": \"...\", \"image\": [x, y]} (pixels)");
            return session.move(j["name"].get<std::string>(), Vec2(j["image"][0].get<double>(), j["image"][1].get<double>()));
        });
    });
    svr.Post("/api/save", [&](const httplib::Request&, httplib::Response& res) {
        guarded(m, res, [&] {
            session.save();
            return nlohmann::json{{"saved", features_path}};
        });
    });
    // Only pages of this server may use it: a request must name this server as its Host (a page
    // elsewhere that rebinds a DNS name to 127.0.0.1 names its own), and a change must come as
    // application/json, which a page of another origin cannot send without the browser asking first
    // (a preflight this server never grants).
    svr.set_pre_routing_handler([&](const httplib::Request& req, httplib::Response& res) {
        const std::string host = req.get_header_value("Host");
        const std::string port_suffix = ":" + std::to_string(svr_port);
        const bool ours = host == a.host + port_suffix || host == "localhost" + port_suffix ||
                          host == "127.0.0.1" + port_suffix || host == "[::1]" + port_suffix;
        if (!ours) {
            reply(res, 403, {{"error", "Host " + host + " is not this server"}, {"exit_code", int(kExitBadInput)}});
            return httplib::Server::HandlerResponse::Handled;
        }
        if (req.method != "GET" && req.method != "HEAD" &&
            req.get_header_value("Content-Type").rfind("application/json", 0) != 0) {
            reply(res, 415, {{"error", "changes must be sent as application/json"}, {"exit_code", int(kExitBadInput)}});
            return httplib::Server::HandlerResponse::Handled;
        }
        return httplib::Server::HandlerResponse::Unhandled;
    });
    auto file_route = [&](const std::string& name, const char* type, bool glb) {
        svr.Get("/api/" + name, [&, name, type, glb](const httplib::Request&, httplib::Response& res) {
            try {
                std::lock_guard<std::mutex> lock(m);
                if (!session.map()) throw BadInput("features", "no map yet: give features first");
                const TexturedMesh tm = session.map()->textured();
                const std::string image = fs::absolute(session.image_path()).string();
                const std::string bytes = map_file_bytes(name, [&](const fs::path& dir) {
                    if (glb) write_glb(tm, (dir / "map.glb").string(), image);  // the image embedded
                    // The downloaded MTL names the image by its file name: beside the OBJ.
                    else write_obj(tm, (dir / "map.obj").string(), (dir / fs::path(image).filename()).string());
                });
                res.set_content(bytes, type);
            } catch (...) {
                reply_current_error(res);
            }
        });
    };
    file_route("map.obj", "text/plain", false);
    file_route("map.mtl", "text/plain", false);
    file_route("map.glb", "model/gltf-binary", true);
    // The image the features are placed on, as the page shows it.
    const std::string image_bytes = read_input_file(a.image, "image file");
    const std::string image_type = image_bytes.rfind("\x89PNG", 0) == 0 ? "image/png" : "image/jpeg";
    svr.Get("/api/image", [&](const httplib::Request&, httplib::Response& res) { res.set_content(image_bytes, image_type); });
    // The page: static files of the web folder only (httplib refuses paths with "..").
    if (!web.empty()) {
        svr.set_mount_point("/", web);
        if (!fs::is_regular_file(fs::path(web) / "three" / "build" / "three.module.js"))
            std::cerr << "ctmap serve: warning: " << web << "/three has no three.js: the page cannot start "
                      << "(npm ci in web/, scripts/build.sh does it)" << std::endl;
    } else {
        svr.Get("/", [](const httplib::Request&, httplib::Response& res) {
            res.status = 404;
            res.set_content("ctmap serve: the editor page's folder was not found (give --web DIR); the JSON API is "
                            "at /api/state (README, \"ctmap serve\")\n",
                            "text/plain");
        });
    }

    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    const int port = a.port == 0 ? svr.bind_to_any_port(a.host) : (svr.bind_to_port(a.host, a.port) ? a.port : -1);
    svr_port = port;
    if (port < 0)
        throw BadInput(a.host + ":" + std::to_string(a.port), "cannot listen there (in use, or not an address of this machine)");
    std::cout << "ctmap serve: listening on http://" << a.host << ":" << port << "/ (" << a.mesh << ", " << a.image
              << ", " << (session.map() ? std::to_string(session.features().features.size()) + " features mapped"
                                        : std::string("no features yet"))
              << "); Ctrl-C stops" << std::endl;
    if (a.open) {  // the desktop's browser, if there is one; the URL is ours (host and port only)
        const std::string cmd = "xdg-open 'http://" + a.host + ":" + std::to_string(port) + "/' >/dev/null 2>&1 &";
        if (std::system(cmd.c_str()) != 0) std::cerr << "ctmap serve: could not start a browser (xdg-open)" << std::endl;
    }
    std::thread watcher([&] {
        while (!g_stop) std::this_thread::sleep_for(std::chrono::milliseconds(100));
        svr.stop();
    });
    const bool ok = svr.listen_after_bind();
    const bool asked = g_stop;  // stopped by SIGINT/SIGTERM, not by a failure of the listener
    g_stop = true;
    watcher.join();
    if (!asked) {
        std::cerr << "ctmap: internal error: the server stopped listening" << std::endl;
        return kExitInternal;
    }
    if (!a.quiet) std::cout << "ctmap serve: stopped" << std::endl;
    return ok || asked ? kExitOk : kExitInternal;
}

}  // namespace

Command add_serve_command(CLI::App& app) {
    auto a = std::make_shared<ServeArgs>();
    auto* sub = app.add_subcommand(
        "serve", "Edit features live: an HTTP server on localhost whose JSON API re-maps (certified) on every change");
    sub->add_option("MESH", a->mesh, "the mesh (a topological disc: OFF/OBJ/PLY/STL)")->required();
    sub->add_option("IMAGE", a->image, "the image (PNG/JPEG)")->required();
    sub->add_option("FEATURES", a->features,
                    "features file (.json): read if it exists; /api/save writes it (the only file the server writes)");
    sub->add_option("--port", a->port, "TCP port (0: any free port, printed)")->capture_default_str()->check(CLI::Range(0, 65535));
    sub->add_option("--host", a->host, "address to listen on (default: this machine only)")->capture_default_str();
    sub->add_option("--snap", a->snap, "how far a point feature may be off the surface (mesh units)")
        ->check(CLI::NonNegativeNumber);
    sub->add_option("--border", a->border, "auto: place border features where needed; given: the paper's rules")
        ->capture_default_str()
        ->check(CLI::IsMember({"auto", "given"}));
    sub->add_option("--web", a->web, "folder of the editor page (default: web/ beside the program)");
    sub->add_flag("--full", a->full, "every move runs the whole pipeline (default: a move starts from the last map when it can)");
    sub->add_flag("--open", a->open, "open the page in the desktop's browser (xdg-open)");
    sub->add_flag("-q,--quiet", a->quiet, "print only the listening line");
    return {sub, [a] { return run_serve(*a); }};
}

}  // namespace ctmap::cli
