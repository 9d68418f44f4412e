package io.etherware.services.network;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import java.io.BufferedInputStream;
import java.io.BufferedOutputStream;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.time.Duration;
import java.util.concurrent.TimeUnit;
import org.HdrHistogram.Histogram;

/**
 * Loopback round trip through two NetworkMessengers (a request from outside node a to an echo
 * component on node b and its reply: XML encoded and decoded at both ends, each node's kernel and
 * dispatcher in the path) beside a raw TCP ping-pong of the same bytes, and the same ping-pong
 * with the XML codec at both ends, and the kernel's share (the same request to an echo on the
 * requesting node itself), in one run. The phases alternate over several rounds so that
 * a change of load on the shared machine hits them alike. Not part of the test suite.
 *
 * <p>Argument: round trips measured per phase (default 60,000), after 20,000 of warm-up each.
 */
public final class LoopbackHarness {

    private static final int WARMUP = 20_000;
    private static final int ROUNDS = 3;
    private static final Profile ECHO = Profile.of("echo");
    private static final Text PAYLOAD = new Text("ping");

    private LoopbackHarness() {
    }

    @FunctionalInterface
    private interface RoundTrip {
        void run() throws Exception;
    }

    public static void main(String[] args) throws Exception {
        int measured = args.length > 0 ? Integer.parseInt(args[0]) : 60_000;
        var messenger = new Histogram(TimeUnit.SECONDS.toNanos(10), 3);
        var raw = new Histogram(TimeUnit.SECONDS.toNanos(10), 3);
        var rawXml = new Histogram(TimeUnit.SECONDS.toNanos(10), 3);
        var inProcess = new Histogram(TimeUnit.SECONDS.toNanos(10), 3);
        var codec = new MessageCodec();
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()))) {
            b.node.add(ECHO, () -> (message, context) -> context.reply(message, message.contents()));
            if (!a.net.awaitResolvable(ECHO, Duration.ofSeconds(30))) {
                throw new IllegalStateException("b's echo was never announced to a");
            }
            QoS qos = QoS.of(Criticality.HIGH);
            long timeoutNs = TimeUnit.SECONDS.toNanos(10);
            RoundTrip throughMessengers = () -> a.node.requestBlocking(ECHO, PAYLOAD, qos, timeoutNs);
            // The kernel's own share: the same request to an echo on the same node (no network).
            Profile localEcho = Profile.of("echo", "node", "a");
            a.node.add(localEcho, () -> (message, context) -> context.reply(message, message.contents()));
            RoundTrip withinNode = () -> a.node.requestBlocking(localEcho, PAYLOAD, qos, timeoutNs);
            // The same bytes as the messengers carry: a request and its reply as encoded on the wire.
            Message request = new Message(ECHO, a.node.profile(), a.node.clock().epochNanos(), qos, PAYLOAD,
                    new MessageId("a", 123_456), null);
            Message reply = new Message(a.node.profile(), ECHO, b.node.clock().epochNanos(), qos, PAYLOAD,
                    new MessageId("b", 654_321), request.messageId());
            byte[] requestXml = codec.encode(request);
            byte[] replyXml = codec.encode(reply);
            try (var pingPong = new RawPingPong(requestXml, replyXml, null);
                 var pingPongXml = new RawPingPong(requestXml, replyXml, codec)) {
                warm(throughMessengers);
                warm(withinNode);
                warm(pingPong::roundTrip);
                warm(pingPongXml::roundTrip);
                for (int round = 0; round < ROUNDS; round++) {
                    record(raw, measured / ROUNDS, pingPong::roundTrip);
                    record(rawXml, measured / ROUNDS, pingPongXml::roundTrip);
                    record(messenger, measured / ROUNDS, throughMessengers);
                    record(inProcess, measured / ROUNDS, withinNode);
                }
            }
            System.out.printf("%nLoopback round trip, %d measured per phase after %d warm-up, %d alternating rounds;"
                    + " request %d B, reply %d B of XML%n", measured, WARMUP, ROUNDS, requestXml.length, replyXml.length);
            System.out.printf("%-44s %8s %8s %8s %8s %8s%n", "us", "p50", "p90", "p99", "p99.9", "max");
            print("raw TCP ping-pong, same bytes", raw);
            print("raw TCP ping-pong + XML codec at both ends", rawXml);
            print("NetworkMessenger request/reply", messenger);
            print("kernel request/reply within one node", inProcess);
            System.out.printf("a: %s%nb: %s%n", a.net.stats(), b.net.stats());

        }
    }

    private static void warm(RoundTrip roundTrip) throws Exception {
        for (int i = 0; i < WARMUP; i++) {
            roundTrip.run();
        }
    }

    private static void record(Histogram histogram, int count, RoundTrip roundTrip) throws Exception {
        for (int i = 0; i < count; i++) {
            long startNs = System.nanoTime();
            roundTrip.run();
            histogram.recordValue(System.nanoTime() - startNs);
        }
    }

    private static void print(String what, Histogram histogram) {
        System.out.printf("%-44s %8.1f %8.1f %8.1f %8.1f %8.1f%n", what, histogram.getValueAtPercentile(50) / 1e3,
                histogram.getValueAtPercentile(90) / 1e3, histogram.getValueAtPercentile(99) / 1e3,
                histogram.getValueAtPercentile(99.9) / 1e3, histogram.getMaxValue() / 1e3);
    }

    /**
     * A client and an echo thread over loopback TCP with TCP_NODELAY, framed with a 4-byte length
     * like the messenger's frames; with a codec, each end decodes what it reads and encodes what
     * it writes, as the messengers do.
     */
    private static final class RawPingPong implements AutoCloseable {
        private final ServerSocket server;
        private final Socket client;
        private final DataOutputStream out;
        private final DataInputStream in;
        private final byte[] requestXml;
        private final byte[] replyXml;
        private final MessageCodec codec;
        private final Message request;
        private final Thread echo;

        RawPingPong(byte[] requestXml, byte[] replyXml, MessageCodec codec) throws IOException {
            this.requestXml = requestXml;
            this.replyXml = replyXml;
            this.codec = codec;
            this.request = codec == null ? null : codec.decode(requestXml);
            server = new ServerSocket(0, 1, InetAddress.getLoopbackAddress());
            client = new Socket(InetAddress.getLoopbackAddress(), server.getLocalPort());
            client.setTcpNoDelay(true);
            Socket accepted = server.accept();
            accepted.setTcpNoDelay(true);
            out = new DataOutputStream(new BufferedOutputStream(client.getOutputStream()));
            in = new DataInputStream(new BufferedInputStream(client.getInputStream()));
            Message reply = codec == null ? null : codec.decode(replyXml);
            echo = Thread.ofPlatform().daemon().name("raw-echo").start(() -> serve(accepted, reply));
        }

        private void serve(Socket socket, Message reply) {
            try (socket;
                 var input = new DataInputStream(new BufferedInputStream(socket.getInputStream()));
                 var output = new DataOutputStream(new BufferedOutputStream(socket.getOutputStream()))) {
                while (true) {
                    byte[] frame = new byte[input.readInt()];
                    input.readFully(frame);
                    byte[] answer = replyXml;
                    if (codec != null) {
                        codec.decode(frame);
                        answer = codec.encode(reply);
                    }
                    output.writeInt(answer.length);
                    output.write(answer);
                    output.flush();
                }
            } catch (IOException e) {
                // Closed.
            }
        }

        void roundTrip() throws IOException {
            byte[] frame = codec == null ? requestXml : codec.encode(request);
            out.writeInt(frame.length);
            out.write(frame);
            out.flush();
            byte[] answer = new byte[in.readInt()];
            in.readFully(answer);
            if (codec != null) {
                codec.decode(answer);
            }
        }

        @Override
        public void close() throws IOException {
            client.close();
            server.close();
            try {
                echo.join(1_000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
    }
}
