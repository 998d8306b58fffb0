// What lcm-spy does with each message, without its window: the class of the message's
// fingerprint from lcm-spy's own type database (lcm.spy.LCMTypeDatabase, which scans the
// CLASSPATH as lcm-spy does), then the message decoded with it. Run by lcm_log_test.py in
// Java's source-file mode:
//   java -cp /usr/share/java/lcm.jar:build/host/java/cyclopion_lcm.jar SpyDecode.java LOG [REGEX]
// Only the channels matching REGEX (default: all). Prints "CHANNEL CLASS COUNT" per channel;
// exit 1 when a message has no known type.
import java.io.ByteArrayInputStream;
import java.io.DataInput;
import java.io.DataInputStream;
import java.io.EOFException;
import java.util.Map;
import java.util.TreeMap;
import lcm.logging.Log;
import lcm.spy.LCMTypeDatabase;

public class SpyDecode {
    public static void main(String[] args) throws Exception {
        LCMTypeDatabase db = new LCMTypeDatabase();
        Log log = new Log(args[0], "r");
        Map<String, Integer> counts = new TreeMap<>();
        String only = args.length > 1 ? args[1] : ".*";
        int unknown = 0;
        while (true) {
            Log.Event ev;
            try {
                ev = log.readNext();
            } catch (EOFException e) {
                break;
            }
            if (!ev.channel.matches(only))
                continue;
            if (ev.data.length < 8) {
                System.out.println("UNKNOWN " + ev.channel + " (no fingerprint)");
                unknown++;
                continue;
            }
            long fingerprint = new DataInputStream(new ByteArrayInputStream(ev.data)).readLong();
            Class<?> cls = db.getClassByFingerprint(fingerprint);
            if (cls == null) {
                System.out.println("UNKNOWN " + ev.channel);
                unknown++;
                continue;
            }
            DataInput in = new DataInputStream(new ByteArrayInputStream(ev.data));
            cls.getConstructor(DataInput.class).newInstance(in); // throws on bad data
            counts.merge(ev.channel + " " + cls.getName(), 1, Integer::sum);
        }
        for (Map.Entry<String, Integer> e : counts.entrySet())
            System.out.println(e.getKey() + " " + e.getValue());
        System.exit(unknown == 0 ? 0 : 1);
    }
}
