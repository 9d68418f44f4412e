package io.etherware.core.codec;

import io.etherware.core.codec.TestContents.Angles;
import io.etherware.core.codec.TestContents.CounterState;
import io.etherware.core.codec.TestContents.Everything;
import io.etherware.core.codec.TestContents.Holder;
import io.etherware.core.codec.TestContents.LogLine;
import io.etherware.core.codec.TestContents.Mode;
import io.etherware.core.codec.TestContents.Node;
import io.etherware.core.codec.TestContents.Point;
import io.etherware.core.codec.TestContents.Samples;
import io.etherware.core.codec.TestContents.Typed;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.message.Tick;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Random;

/** Seeded random messages over every envelope variant and every contents shape of {@link TestContents}. */
final class MessageGenerator {

    private static final String NAME_START = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_";
    private static final String NAME_REST = NAME_START + ".-";
    private static final String VALUE_CHARS = NAME_START + ".:/@+-";
    /** Pieces of text that stress XML escaping, line ends, whitespace and Unicode. */
    private static final String[] TEXT_PIECES = {
            "<", ">", "&", "'", "\"", "]]>", "&amp;", "<![CDATA[", "-->", "<?pi?>", " ", "  ", "\t", "\n", "\r",
            "\r\n", "é", "中文", "\uE000", "\uFFFD", "\uD83D\uDE00", "\uDBFF\uDFFF", "Ω", "\u00A0", "\u2028",
            "plain", "x", "",
    };
    private static final double[] SPECIAL_DOUBLES = {
            0.0, -0.0, Double.NaN, Double.POSITIVE_INFINITY, Double.NEGATIVE_INFINITY, Double.MIN_VALUE,
            Double.MAX_VALUE, -Double.MAX_VALUE, Double.MIN_NORMAL, 1e-300, 0.1, 1.0 / 3,
    };
    private static final long[] SPECIAL_LONGS = {0, 1, -1, Long.MIN_VALUE, Long.MAX_VALUE};

    private final Random random;

    MessageGenerator(long seed) {
        random = new Random(seed);
    }

    /** Every combination of criticality and present/absent period, deadline and WCET: 32 QoS values. */
    static List<QoS> allQosCombinations() {
        var all = new ArrayList<QoS>();
        for (Criticality criticality : Criticality.values()) {
            for (int mask = 0; mask < 8; mask++) {
                all.add(new QoS(criticality, (mask & 1) != 0 ? 15_000_000 : 0, (mask & 2) != 0 ? 12_000_000 : 0,
                        (mask & 4) != 0 ? 2_000_000 : 0));
            }
        }
        return all;
    }

    /** Message number {@code index}: its QoS cycles through all 32 combinations. */
    Message message(int index) {
        List<QoS> qos = allQosCombinations();
        return new Message(profile(), random.nextBoolean() ? profile() : null, someLong(), qos.get(index % qos.size()),
                contents(), messageId(), random.nextBoolean() ? messageId() : null);
    }

    Profile profile() {
        var attributes = new LinkedHashMap<String, String>();
        int count = random.nextInt(4);
        while (attributes.size() < count) {
            attributes.put(name(), token(VALUE_CHARS, VALUE_CHARS, 1 + random.nextInt(8)));
        }
        return new Profile(name(), attributes);
    }

    MessageId messageId() {
        return new MessageId(name(), random.nextInt(4) == 0 ? Long.MAX_VALUE : random.nextLong(0, Long.MAX_VALUE));
    }

    Contents contents() {
        return switch (random.nextInt(10)) {
            case 0 -> Empty.INSTANCE;
            case 1 -> new Text(text(random.nextInt(60)));
            case 2 -> new Tick(someLong(), random.nextLong(0, Long.MAX_VALUE), random.nextLong(0, 1_000_000_000));
            case 3 -> new Angles(random.nextLong(), random.nextInt(), random.nextInt(), random.nextLong());
            case 4 -> everything();
            case 5 -> samples(random.nextInt(20));
            case 6 -> new Holder(random.nextBoolean() ? null : new Tick(1, 2, 3), counterState(),
                    List.of(Empty.INSTANCE, new Text(text(10)), counterState()));
            case 7 -> new LogLine(text(30), random.nextBoolean() ? null : "WARN");
            case 8 -> Node.chain(1 + random.nextInt(10));
            default -> new Typed(text(8), random.nextInt());
        };
    }

    Everything everything() {
        return new Everything(random.nextBoolean(), (byte) random.nextInt(), (short) random.nextInt(), xmlChar(),
                random.nextInt(), someLong(), someFloat(), someDouble(),
                random.nextBoolean() ? null : random.nextBoolean(), random.nextBoolean() ? null : random.nextInt(),
                random.nextBoolean() ? null : someLong(), random.nextBoolean() ? null : someDouble(),
                random.nextBoolean() ? null : xmlChar(),
                random.nextInt(5) == 0 ? null : text(20), Mode.values()[random.nextInt(3)], profile(), messageId(),
                random.nextBoolean() ? null : new Point(someDouble(), someDouble()),
                List.of(new Point(1.5, -2.5), new Point(someDouble(), someDouble())),
                random.nextBoolean() ? List.of() : java.util.Arrays.asList(text(5), null, "", "  "),
                List.of(someLong(), someLong()),
                List.of(List.of(), List.of(1, 2, 3), List.of(random.nextInt())),
                List.of(Mode.FAULT, Mode.IDLE));
    }

    Samples samples(int length) {
        var values = new double[length];
        var stamps = new long[length];
        var counts = new int[length];
        var raw = new byte[length * 3];
        for (int i = 0; i < length; i++) {
            values[i] = someDouble();
            stamps[i] = someLong();
            counts[i] = random.nextInt();
        }
        random.nextBytes(raw);
        return new Samples(values, stamps, counts, random.nextInt(5) == 0 ? null : raw);
    }

    CounterState counterState() {
        return new CounterState(random.nextLong(), text(6));
    }

    /** Random text of about {@code pieces} pieces, including XML specials, CRs and surrogate pairs. */
    String text(int pieces) {
        var text = new StringBuilder();
        for (int i = 0; i < pieces; i++) {
            if (random.nextBoolean()) {
                text.append(TEXT_PIECES[random.nextInt(TEXT_PIECES.length)]);
            } else {
                text.appendCodePoint(xmlCodePoint());
            }
        }
        return text.toString();
    }

    /** Any code point XML 1.0 allows, biased towards ASCII. */
    int xmlCodePoint() {
        return switch (random.nextInt(4)) {
            case 0 -> 0x20 + random.nextInt(0x5F);
            case 1 -> 0xA0 + random.nextInt(0xD800 - 0xA0);
            case 2 -> 0xE000 + random.nextInt(0xFFFE - 0xE000);
            default -> 0x10000 + random.nextInt(0x110000 - 0x10000);
        };
    }

    char xmlChar() {
        int codePoint;
        do {
            codePoint = xmlCodePoint();
        } while (codePoint > 0xFFFF);
        return (char) codePoint;
    }

    long someLong() {
        return random.nextInt(4) == 0 ? SPECIAL_LONGS[random.nextInt(SPECIAL_LONGS.length)] : random.nextLong();
    }

    double someDouble() {
        return random.nextInt(3) == 0 ? SPECIAL_DOUBLES[random.nextInt(SPECIAL_DOUBLES.length)]
                : Double.longBitsToDouble(random.nextLong());
    }

    float someFloat() {
        return random.nextInt(3) == 0 ? (float) SPECIAL_DOUBLES[random.nextInt(SPECIAL_DOUBLES.length)]
                : Float.intBitsToFloat(random.nextInt());
    }

    private String name() {
        return token(NAME_START, NAME_REST, 1 + random.nextInt(10));
    }

    private String token(String first, String rest, int length) {
        var token = new StringBuilder().append(first.charAt(random.nextInt(first.length())));
        for (int i = 1; i < length; i++) {
            token.append(rest.charAt(random.nextInt(rest.length())));
        }
        return token.toString();
    }
}
