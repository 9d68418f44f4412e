package io.etherware.deploy.view;

import com.sun.net.httpserver.HttpExchange;
import com.sun.net.httpserver.HttpServer;
import io.etherware.services.status.NodeStatus;
import java.io.IOException;
import java.io.InputStream;
import java.io.OutputStream;
import java.io.UncheckedIOException;
import java.net.InetSocketAddress;
import java.nio.charset.StandardCharsets;
import java.util.Locale;
import java.util.Objects;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A live view of a running node over HTTP, on the JDK's own server ({@code jdk.httpserver}):
 * <ul>
 *   <li>{@code /}: one self-contained page (no external script, style or font) that polls the two
 *       documents below twice a second and shows the node, its peers, components, dispatchers and
 *       a plot of every live signal;</li>
 *   <li>{@code /status.json}: the node's status ({@link NodeStatus}) as JSON;</li>
 *   <li>{@code /signals.json}: the live signals' samples;</li>
 *   <li>{@code /metrics}: the status and the signals' newest values in the Prometheus text format
 *       0.0.4, for a scraper.</li>
 * </ul>
 * Read-only: GET and HEAD only (anything else is 405), no request body is read, and on loopback a
 * request whose {@code Host} is not a loopback name is refused (403), so a web page elsewhere cannot
 * read the view through DNS rebinding.
 *
 * <p>Runs on {@value #THREADS} ordinary daemon threads of its own, never at real-time priority: a
 * request reads the status and copies the signals, and never holds up a dispatcher.
 * Thread-safe; {@link #close} may come from any thread.
 */
public final class NodeView implements AutoCloseable {

    /** Threads serving requests. */
    public static final int THREADS = 2;

    private static final Logger LOG = LoggerFactory.getLogger(NodeView.class);
    private static final String PAGE_RESOURCE = "view.html";
    /** What the page may load: its own inline script and style, and documents from this server. */
    private static final String PAGE_POLICY = "default-src 'none'; script-src 'unsafe-inline';"
            + " style-src 'unsafe-inline'; connect-src 'self'; img-src 'self' data:; base-uri 'none';"
            + " form-action 'none'; frame-ancestors 'none'";

    private final ViewConfig config;
    private final Supplier<NodeStatus> status;
    private final LiveSignals signals;
    private final byte[] page;
    private final HttpServer server;
    private final ExecutorService executor;

    private NodeView(ViewConfig config, Supplier<NodeStatus> status, LiveSignals signals, byte[] page,
            HttpServer server, ExecutorService executor) {
        this.config = config;
        this.status = status;
        this.signals = signals;
        this.page = page;
        this.server = server;
        this.executor = executor;
    }

    /**
     * Binds {@code config.listen()} and starts serving.
     *
     * @param config  where to listen
     * @param status  reads the node's status now; called on the view's threads
     * @param signals the node's live signals
     * @return the running view
     * @throws IOException if the address cannot be bound (in use, not this host's)
     */
    public static NodeView start(ViewConfig config, Supplier<NodeStatus> status, LiveSignals signals)
            throws IOException {
        Objects.requireNonNull(config, "config");
        Objects.requireNonNull(status, "status");
        Objects.requireNonNull(signals, "signals");
        byte[] page;
        try (InputStream in = NodeView.class.getResourceAsStream(PAGE_RESOURCE)) {
            page = Objects.requireNonNull(in, PAGE_RESOURCE).readAllBytes();
        }
        HttpServer server = HttpServer.create(config.listen(), 16);
        ExecutorService executor = Executors.newFixedThreadPool(THREADS,
                Thread.ofPlatform().daemon().name("node-view-", 0).factory());
        var view = new NodeView(config, status, signals, page, server, executor);
        server.createContext("/", view::handle);
        server.setExecutor(executor);
        server.start();
        LOG.info("view on http://{}/", hostPort(view.address()));
        return view;
    }

    /** {@return the address the view listens on (the real port where the configuration said 0)} */
    public InetSocketAddress address() {
        return server.getAddress();
    }

    /**
     * {@return the view's page address, e.g. {@code http://127.0.0.1:8080/}}
     */
    public String url() {
        return "http://" + hostPort(address()) + "/";
    }

    private static String hostPort(InetSocketAddress address) {
        String host = address.getAddress().getHostAddress();
        return (host.contains(":") ? "[" + host + "]" : host) + ":" + address.getPort();
    }

    /** Stops listening and ends the view's threads; requests being answered get up to a second. */
    @Override
    public void close() {
        server.stop(1);
        executor.shutdownNow();
    }

    private void handle(HttpExchange exchange) throws IOException {
        try (exchange) {
            var headers = exchange.getResponseHeaders();
            headers.set("Cache-Control", "no-store");
            headers.set("X-Content-Type-Options", "nosniff");
            String method = exchange.getRequestMethod();
            boolean head = method.equals("HEAD");
            if (!method.equals("GET") && !head) {
                headers.set("Allow", "GET, HEAD");
                send(exchange, 405, "text/plain; charset=utf-8", "405 only GET and HEAD: the view is read-only\n",
                        false);
                return;
            }
            if (!config.allowRemote() && !loopbackHost(exchange.getRequestHeaders().getFirst("Host"))) {
                send(exchange, 403, "text/plain; charset=utf-8", "403 this view answers loopback names only\n", head);
                return;
            }
            switch (exchange.getRequestURI().getPath()) {
                case "/", "/index.html" -> {
                    headers.set("Content-Security-Policy", PAGE_POLICY);
                    send(exchange, 200, "text/html; charset=utf-8", page, head);
                }
                case "/status.json" -> send(exchange, 200, "application/json", ViewJson.status(status.get()), head);
                case "/signals.json" -> send(exchange, 200, "application/json", ViewJson.signals(signals.signals()),
                        head);
                case "/metrics" -> send(exchange, 200, MetricsText.CONTENT_TYPE,
                        MetricsText.of(status.get(), signals.signals()), head);
                default -> send(exchange, 404, "text/plain; charset=utf-8", "404 not here: try /, /status.json,"
                        + " /signals.json or /metrics\n", head);
            }
        } catch (IOException | UncheckedIOException e) {
            LOG.debug("view: a request ended early: {}", e.toString()); // the client went away
        } catch (RuntimeException e) {
            LOG.warn("view: a request failed", e);
        }
    }

    /** Whether a request's {@code Host} names this host's loopback (absent: an HTTP/1.0 client; allowed). */
    static boolean loopbackHost(String host) {
        if (host == null) {
            return true;
        }
        String name = host.strip().toLowerCase(Locale.ROOT);
        if (name.startsWith("[")) {
            int close = name.indexOf(']');
            name = close < 0 ? name : name.substring(1, close);
        } else if (name.indexOf(':') >= 0) {
            name = name.substring(0, name.indexOf(':'));
        }
        return name.equals("localhost") || name.equals("::1") || name.matches("127(\\.[0-9]{1,3}){3}");
    }

    private static void send(HttpExchange exchange, int status, String type, String body, boolean head)
            throws IOException {
        send(exchange, status, type, body.getBytes(StandardCharsets.UTF_8), head);
    }

    private static void send(HttpExchange exchange, int status, String type, byte[] body, boolean head)
            throws IOException {
        exchange.getResponseHeaders().set("Content-Type", type);
        if (head) {
            exchange.sendResponseHeaders(status, -1);
            return;
        }
        exchange.sendResponseHeaders(status, body.length);
        try (OutputStream out = exchange.getResponseBody()) {
            out.write(body);
        }
    }
}
