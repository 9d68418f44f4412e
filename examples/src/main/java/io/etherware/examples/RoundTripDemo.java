package io.etherware.examples;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import java.nio.charset.StandardCharsets;
import java.util.concurrent.TimeUnit;

/**
 * The smallest end-to-end look at Etherware's wire format: a 15 ms HIGH-criticality Tick for
 * the pendulum controller, encoded as the XML document that crosses the network and decoded
 * back to an equal message.
 */
public final class RoundTripDemo {

    private RoundTripDemo() {
    }

    public static void main(String[] args) {
        long periodNs = TimeUnit.MILLISECONDS.toNanos(15);
        Message tick = new Message(
                Profile.parse("controller[plant=pendulum,node=2]"),
                Profile.of("notifier"),
                System.currentTimeMillis() * 1_000_000L,
                QoS.periodic(Criticality.HIGH, periodNs),
                new Tick(System.nanoTime(), 0, periodNs),
                new MessageId("node-2", 1),
                null);

        MessageCodec codec = new MessageCodec(new io.etherware.core.message.ContentsTypes());
        byte[] xml = codec.encode(tick);
        Message decoded = codec.decode(xml);

        System.out.println(new String(xml, StandardCharsets.UTF_8));
        System.out.printf("%d bytes of XML; decoded message equals the original: %b%n",
                xml.length, decoded.equals(tick));
        if (!decoded.equals(tick)) {
            System.exit(1);
        }
    }
}
